#pragma once
// Touchdown at a minimum downward foot speed (landing with an impact only): the swing foot meets
// the ground at V2z⁻ ≤ −v_min, so that a vertical tracking error Δz of the foot moves the
// touchdown by about Δz / v_min (1 mm at 0.5 m/s: 2 ms). The zero-velocity landing of the thesis
// (3.20) meets the ground tangentially, where the same error moves touchdown by ~10 ms.
#include "gaitopt/gait/constraints/group_spec.hpp"

namespace gaitopt {

// V2z⁻ = −α̇⁻ v2z, v2z the arriving foot's vertical speed per unit rate α̇⁻ = −1 rad/s
// (gait/impact_landing.hpp, LandingImpact::v2_minus) and α̇⁻ = α̇_fSS < 0: V2z⁻ + v_min ≤ 0.
template <class S>
S touchdownSpeedRow(const S& v2z_per_unit_rate, const S& alphadot_minus, double v_min) {
  return -alphadot_minus * v2z_per_unit_rate + v_min;
}

// Foot speeds of a walking step are of the order of 1 m/s.
inline double footSpeedScale(const Model&) { return 1.0; }

constexpr ConstraintGroupSpec kTouchdownSpeedSpec{"touchdown_speed", 5, "(2.2)", "m/s",
    footSpeedScale, ConstraintPhase::None, 1, 0, ConstraintPresence::WithTouchdownSpeed};

}  // namespace gaitopt
