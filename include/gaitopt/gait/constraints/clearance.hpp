#pragma once
// Clearance of the swing foot (3.49): above the parabola h (1 − x²) of its horizontal position
// x relative to the step length, on the open SS (the foot is on the ground at both ends).
#include "gaitopt/gait/constraints/group_spec.hpp"

namespace gaitopt {

// The required foot height at x = x_foot2 / d.
template <class S> S clearanceProfile(const S& x, double height) { return height * (1.0 - x * x); }

// z_foot2 ≥ the profile.
template <class S> S clearanceRow(const S& foot_height, const S& profile) {
  return -(foot_height - profile);
}

inline double clearanceScale(const Model&) { return 0.05; }

constexpr ConstraintGroupSpec kClearanceSpec{"clearance", 5, "(3.49)", "m", clearanceScale,
                                             ConstraintPhase::SingleSupport, 1, 1};

}  // namespace gaitopt
