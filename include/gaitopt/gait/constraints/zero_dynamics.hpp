#pragma once
// Existence of the SS zero dynamics (levels 2–4): the inertia coefficient f of α stays positive
// (3.45), the SS starts moving forward (3.15) and never falls back (3.44), and the DS after a
// touchdown without impact keeps α moving (κ > 0, (3.23)).
#include "gaitopt/gait/constraints/group_spec.hpp"

namespace gaitopt {

// (3.45): f(α) ≥ f_min.
template <class S> S fPositiveRow(const S& f, double f_min) { return f_min - f; }

// (3.15): α̇_iSS ≤ −margin.
template <class S> S alphadotNegativeRow(const S& alphadot_iSS, double margin) {
  return alphadot_iSS + margin;
}
// Without DS the start rate is cyclic, α̇_iSS² = r² Φ_f / ((1 − r²) f_i²)
// (gait/zero_dynamics.hpp): α̇_iSS² ≥ margin², multiplied by 1 − r² so that it stays finite as
// r² → 1.
template <class S>
S alphadotCyclicRow(const S& r2, const S& phi_f, const S& f_iSS, double margin) {
  return margin * margin * (1.0 - r2) - r2 * phi_f / S(f_iSS * f_iSS);
}

// (3.44), (3.55) divided by f_i²: σ²/f_i² = Φ/f_i² + α̇_iSS² ≥ margin².
template <class S>
S noFallBackRow(const S& phi, const S& f_iSS, const S& alphadot_iSS, double margin) {
  return -(phi / S(f_iSS * f_iSS) + alphadot_iSS * alphadot_iSS) + margin * margin;
}

// (3.23): κ ≥ κ_min.
template <class S> S kappaPositiveRow(const S& kappa, double kappa_min) { return kappa_min - kappa; }

inline double fScale(const Model&) { return 10.0; }

constexpr ConstraintGroupSpec kFPositiveSpec{"f_positive", 2, "(3.45)", "kg m^2", fScale,
                                             ConstraintPhase::SingleSupport};
// Without DS the row is alphadotCyclicRow, in (rad/s)^2.
constexpr ConstraintGroupSpec kAlphadotNegativeSpec{
    "alphadot_iSS_negative", 3, "(3.15)", "rad/s", dimensionlessScale, ConstraintPhase::None,
    1, 0, ConstraintPresence::Always, "(rad/s)^2"};
constexpr ConstraintGroupSpec kNoFallBackSpec{"no_fall_back", 3, "(3.44), (3.55)", "(rad/s)^2",
                                              dimensionlessScale, ConstraintPhase::SingleSupport};
constexpr ConstraintGroupSpec kKappaPositiveSpec{"kappa_positive", 4, "(3.23)", "1",
    dimensionlessScale, ConstraintPhase::None, 1, 0, ConstraintPresence::WithoutImpact};

}  // namespace gaitopt
