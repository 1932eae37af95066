#pragma once
// Software joint limits (3.39), (3.42) on the knee angles δ1, δ4 and the hip angles δ2, δ2 + δ3,
// kept with a margin.
#include <array>

#include "gaitopt/gait/constraints/group_spec.hpp"
#include "gaitopt/math/types.hpp"
#include "gaitopt/model/robot_params.hpp"

namespace gaitopt {

// The limited angles of a configuration q = (α, δ1, δ2, δ3, δ4): knee 1, hip 1, hip 2, knee 2.
template <class S> std::array<S, 4> jointLimitAngles(const Vector5<S>& q) {
  return {q(1), q(2), q(2) + q(3), q(4)};
}

// (3.42): the rows (upper, lower) of limited angle j.
template <class S>
std::array<S, 2> jointLimitRows(const JointLimits& limits, int j, const S& angle, double margin) {
  const bool knee = j == 0 || j == 3;
  const double lo = knee ? limits.knee_min : limits.hip_min;
  const double hi = knee ? limits.knee_max : limits.hip_max;
  return {angle - hi + margin, lo - angle + margin};
}

constexpr ConstraintGroupSpec kJointLimitsSsSpec{"joint_limits_ss", 5, "(3.42)", "rad",
    dimensionlessScale, ConstraintPhase::SingleSupport, 8};
constexpr ConstraintGroupSpec kJointLimitsDsSpec{"joint_limits_ds", 5, "(3.42)", "rad",
    dimensionlessScale, ConstraintPhase::DoubleSupport, 8};

}  // namespace gaitopt
