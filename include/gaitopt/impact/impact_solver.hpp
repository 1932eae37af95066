#pragma once
// The algebraic (App. C enumeration) and differential (Keller; phases in the normal impulse,
// §2.3) impact solvers on the floating model, in double precision.
#include "gaitopt/impact/impact_result.hpp"

namespace gaitopt {

// All 12 behaviours solved, every consistent one returned (§1.3 resolution method).
ImpactResult solveAlgebraicImpact(const ImpactSystem<double>& system, const ImpactOptions& options);

// Sequence of algebraic phases in τ (§2.4–2.5, Table 2.1); indeterminate phases branch,
// repeated phase patterns are summed as geometric series.
ImpactResult solveDifferentialImpact(const ImpactSystem<double>& system,
                                     const ImpactOptions& options);

ImpactResult solveImpact(const Model& model, const Vector7<double>& X,
                         const Vector7<double>& Xd_minus, ImpactModelKind kind,
                         const ImpactOptions& options);

// Pinned configuration q and velocities qd (foot 1 at rest at the origin) → the impact of
// foot 2 (gaitopt impact's input).
ImpactResult solveImpactFromPinned(const Model& model, const Vec5& q, const Vec5& qd,
                                   ImpactModelKind kind, const ImpactOptions& options);

namespace detail {
// Dimensionless scales of the zero tests: velocity scale |V2⁻|, impulse scale |V2⁻| / max W_ii.
struct ImpactScales {
  double speed, impulse;
};
ImpactScales impactScales(const ImpactSystem<double>& system);
// Post-impact floating velocities, energy loss and contact state of total impulses I.
void completeSolution(const ImpactSystem<double>& system, const Eigen::Vector4d& I,
                      const ImpactOptions& options, ImpactSolution& solution);
// Whether two solutions have the same impulses: within `impulse_tolerance` or, for large
// impulses, within the same tolerance relative to their size.
bool sameOutcome(const ImpactSolution& a, const ImpactSolution& b, double impulse_tolerance,
                 double relative_tolerance);
// Algebraic model: appends `s` unless a solution with the same outcome is already there; a
// merged duplicate marks the kept one as boundary (two behaviours meeting at a zone edge).
void addDistinctSolution(std::vector<ImpactSolution>& solutions, ImpactSolution s,
                         double impulse_tolerance, double relative_tolerance);
// inconsistent: no solution; indeterminate: at least two different outcomes; otherwise
// accumulation when some solution went through a summed accumulation, else unique.
ImpactStatus statusOf(const std::vector<ImpactSolution>& solutions, double impulse_tolerance,
                      double relative_tolerance);
}  // namespace detail

}  // namespace gaitopt
