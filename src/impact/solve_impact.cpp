#include "gaitopt/impact/solve_impact.hpp"

#include "gaitopt/model/dynamics_pinned.hpp"

namespace gaitopt {

ImpactResult solveImpact(const Model& model, const Vector7<double>& X,
                         const Vector7<double>& Xd_minus, ImpactModelKind kind,
                         const ImpactOptions& options) {
  const ImpactSystem<double> system = impactSystem(model, X, Xd_minus);
  return kind == ImpactModelKind::Algebraic ? solveAlgebraicImpact(system, options)
                                            : solveDifferentialImpact(system, options);
}

double foot2VerticalVelocity(const Model& model, const Vec5& q, const Vec5& qd) {
  return pinnedTerms(model, q, qd).D2.row(1).dot(qd);
}

ImpactResult solveImpactFromPinned(const Model& model, const Vec5& q, const Vec5& qd,
                                   ImpactModelKind kind, const ImpactOptions& options) {
  Vector7<double> X, Xd;
  floatingStateFromPinned(model, q, qd, X, Xd);
  return solveImpact(model, X, Xd, kind, options);
}

}  // namespace gaitopt
