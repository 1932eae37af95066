#pragma once
// Contact of a stance foot (3.48): its reaction R = (R_x, R_z), in the ground's frame, inside
// the friction cone |R_x| ≤ μ R_z and with a normal force of at least R_min.
#include <algorithm>
#include <array>

#include "gaitopt/gait/constraints/group_spec.hpp"
#include "gaitopt/math/types.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

// (3.48): the friction cone's rows (−R_x ≤ μ R_z, R_x ≤ μ R_z).
template <class S> std::array<S, 2> frictionConeRows(const Vector2<S>& R, double mu) {
  return {-mu * R(1) - R(0), -mu * R(1) + R(0)};
}

// |R_x| − μ R_z: the larger row of the friction cone, for a report of the contact (not smooth).
inline double frictionConeExcess(const Vector2<double>& R, double mu) {
  const std::array<double, 2> rows = frictionConeRows(R, mu);
  return std::max(rows[0], rows[1]);
}

// (3.48): R_z ≥ R_min.
template <class S> S normalForceRow(const Vector2<S>& R, double min_normal_force) {
  return min_normal_force - R(1);
}

inline double weightScale(const Model& m) { return m.total_mass * m.gravity; }

// Per node: the SS stance foot's rows, the DS's for foot 1 then foot 2.
constexpr ConstraintGroupSpec kFrictionConeSsSpec{"friction_cone_ss", 5, "(3.48)", "N", weightScale,
                                                  ConstraintPhase::SingleSupport, 2};
constexpr ConstraintGroupSpec kNormalForceSsSpec{"normal_force_ss", 5, "(3.48)", "N", weightScale,
                                                 ConstraintPhase::SingleSupport, 1};
constexpr ConstraintGroupSpec kFrictionConeDsSpec{"friction_cone_ds", 5, "(3.48)", "N", weightScale,
                                                  ConstraintPhase::DoubleSupport, 4};
constexpr ConstraintGroupSpec kNormalForceDsSpec{"normal_force_ds", 5, "(3.48)", "N", weightScale,
                                                 ConstraintPhase::DoubleSupport, 2};

}  // namespace gaitopt
