#pragma once
// Landing with an impact (gait/impact_landing.hpp): the swing foot arrives moving down (2.2),
// the impact has the required behaviour (2.5), (2.9)–(2.12) (landingConsistency), the rate
// ratio keeps α moving (3.23), and without DS the impact's orbit of the zero dynamics is
// attractive (3.14).
#include "gaitopt/gait/constraints/group_spec.hpp"

namespace gaitopt {

// (2.2): V2z⁻ ≤ −margin, per unit rate [m/s per rad/s].
template <class S> S impactArrivalRow(const S& v2z_minus) {
  constexpr double kArrivalMargin = 1e-3;
  return v2z_minus + kArrivalMargin;
}
// (3.23): the impact's rate ratio λ ≥ κ_min.
template <class S> S impactRateRatioRow(const S& rate_ratio, double kappa_min) {
  return kappa_min - rate_ratio;
}
// (3.14): r² ≤ 1 − margin, r = f_i λ / f_f the impact's ratio of σ = f α̇.
template <class S> S impactOrbitRow(const S& r2) {
  constexpr double kOrbitMargin = 1e-3;
  return r2 - (1.0 - kOrbitMargin);
}

constexpr const char* kImpactRateUnit = "m/s per rad/s";
constexpr ConstraintGroupSpec kImpactArrivalSpec{"impact_arrival", 1, "(2.2)", kImpactRateUnit,
    dimensionlessScale, ConstraintPhase::None, 1, 0, ConstraintPresence::WithImpact};
constexpr ConstraintGroupSpec kImpactConsistencySpec{"impact_consistency", 1,
    "(2.5), (2.9)-(2.12)", kImpactRateUnit, dimensionlessScale, ConstraintPhase::None, 1, 0,
    ConstraintPresence::ImpactSlacks};
constexpr ConstraintGroupSpec kImpactRateRatioSpec{"impact_rate_ratio", 1, "(3.23)", "1",
    dimensionlessScale, ConstraintPhase::None, 1, 0, ConstraintPresence::WithImpact};
constexpr ConstraintGroupSpec kImpactOrbitSpec{"impact_orbit", 3, "(3.14)", "1", dimensionlessScale,
    ConstraintPhase::None, 1, 0, ConstraintPresence::WithoutDoubleSupport};

}  // namespace gaitopt
