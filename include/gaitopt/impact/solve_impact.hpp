#pragma once
// The impact solvers' interface: the algebraic (App. C enumeration) and differential (Keller;
// phases in the normal impulse, §2.3) solvers on the floating model, in double precision, and
// the dispatch on the model kind.
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

// Vertical velocity V2z = D2[1,:] q̇ [m/s] with which foot 2 arrives at pinned configuration q
// and velocities qd (foot 1 at rest at the origin); an impact needs V2z < 0.
double foot2VerticalVelocity(const Model& model, const Vec5& q, const Vec5& qd);

// Pinned configuration q and velocities qd (foot 1 at rest at the origin) → the impact of
// foot 2 (gaitopt impact's input).
ImpactResult solveImpactFromPinned(const Model& model, const Vec5& q, const Vec5& qd,
                                   ImpactModelKind kind, const ImpactOptions& options);

}  // namespace gaitopt
