#pragma once
// Reach of the legs (3.36), (3.37), (3.41): the squared hip-to-foot distance ρ² of a leg stays
// within [margin, L² − margin], L = l4 + l5 the stretched leg.
#include <array>
#include <cmath>

#include "gaitopt/gait/constraints/group_spec.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

// The rows (max, min) of a squared reach ρ².
template <class S> std::array<S, 2> reachRows(const S& rho2, double leg_length, double margin) {
  return {rho2 - leg_length * leg_length + margin, margin - rho2};
}

inline double reachScale(const Model& m) { return std::pow(m.robot.l4 + m.robot.l5, 2); }

constexpr const char* kReachUnit = "m^2";
constexpr ConstraintGroupSpec kReachMaxIdsSpec{"reach_max_iDS", 0, "(3.36)", kReachUnit,
                                               reachScale};
constexpr ConstraintGroupSpec kReachMinIdsSpec{"reach_min_iDS", 0, "(3.36)", kReachUnit,
                                               reachScale};
constexpr ConstraintGroupSpec kReachMaxFdsSpec{"reach_max_fDS", 0, "(3.36)", kReachUnit,
    reachScale, ConstraintPhase::None, 1, 0, ConstraintPresence::WithDoubleSupport};
constexpr ConstraintGroupSpec kReachMinFdsSpec{"reach_min_fDS", 0, "(3.36)", kReachUnit,
    reachScale, ConstraintPhase::None, 1, 0, ConstraintPresence::WithDoubleSupport};
constexpr ConstraintGroupSpec kReachMaxIntSpec{"reach_max_int", 0, "(3.37)", kReachUnit,
                                               reachScale};
constexpr ConstraintGroupSpec kReachMinIntSpec{"reach_min_int", 0, "(3.37)", kReachUnit,
                                               reachScale};
constexpr ConstraintGroupSpec kDsReachMaxSpec{"ds_reach_max", 4, "(3.41)", kReachUnit, reachScale,
                                              ConstraintPhase::DoubleSupport};
constexpr ConstraintGroupSpec kDsReachMinSpec{"ds_reach_min", 4, "(3.41)", kReachUnit, reachScale,
                                              ConstraintPhase::DoubleSupport};

}  // namespace gaitopt
