#pragma once
// Touchdown with a rigid impact (thesis ch. 2) for gaitopt simulate: the impact solvers of
// impact/solve_impact.hpp at the located touchdown, then the leg exchange (3.22)–(3.23).
//
// Model: the algebraic impact (2.1)/(2.13) with Coulomb friction by default — the model the
// impact-landing gaits are optimised with (gait/impact_landing.hpp), so the simulated cycle is
// the optimised one; the differential (Keller) model is available (--impact differential) and
// agrees with it on the shipped gaits (one phase, docs/science/impact-gaits.md).
// Outcomes: status inconsistent or indeterminate → ImpactUnavailable (the model cannot say
// what happens); a foot sliding after the impact → Slipped; foot 1 (rear) lifting when the
// gait needs a double support → RearFootLift. When foot 1 sticks on a gait without double
// support, the new SS starts at once with the rear foot at rest on the ground (released).
#include <string>

#include "gaitopt/gait/options.hpp"
#include "gaitopt/impact/solve_impact.hpp"
#include "gaitopt/sim/closed_loop.hpp"

namespace gaitopt {

// `double_support_gait`: a DS follows the touchdown in the gait's cycle. Below `speed_tol`
// [m/s] of arriving foot speed the touchdown is impulse-free (the impact is 0/0 there).
TouchdownMap impactTouchdown(ImpactModelKind kind, const ImpactOptions& options,
                             bool double_support_gait, double speed_tol = 1e-6);

// The touchdown of a zero-velocity gait that needs a double support, located by foot height:
// the plastic impact with both feet held on the ground (the DS's contact), which a perturbed
// step lands with at small velocity. The stance foot carries ≈ M g before the impact, so over
// an impact of finite duration `impact_duration` [s] it absorbs a pull down to −M g ·
// impact_duration (a rigid impact neglects that finite force); a larger pull, or a foot
// impulse outside its cone (μ `mu`), leaves it to the algebraic rigid impact with friction
// (Slipped; RearFootLift, or with `rear_lift_starts_ss` the next SS at once, the DS skipped).
// Below `speed_tol` [m/s] of arriving foot speed the held impact is always used (its impulses
// are then round-off). 5 ms: a rubber-padded foot's contact time, π√(m/k) for a few kg on
// 10⁵ N/m, is 10–20 ms; 5 ms is the conservative end (an assumption, not a measurement).
TouchdownMap doubleSupportTouchdown(double mu, bool rear_lift_starts_ss,
                                    double impact_duration = 5e-3, double speed_tol = 1e-6);

// The touchdown map of a gait: `model` auto (double_support for a zero-velocity landing of a
// gait with DS, none for one without, algebraic for an impact landing), none (impulse-free
// only), double_support (doubleSupportTouchdown), algebraic or differential, none (impulse-free only), algebraic or differential; impacts with friction
// coefficient `ground_mu` (the plant's ground). Throws std::invalid_argument on another name.
// `model` with auto resolved: none, double_support or algebraic.
std::string resolvedImpactModel(const GaitOptions& options, const std::string& model);
TouchdownMap gaitTouchdown(const GaitOptions& options, const std::string& model, double ground_mu);

}  // namespace gaitopt
