// Algebraic impact: the 12 behaviours of Appendix C enumerated, every consistent one kept.
#include <cmath>

#include "gaitopt/impact/solve_impact.hpp"

namespace gaitopt {

ImpactResult solveAlgebraicImpact(const ImpactSystem<double>& system, const ImpactOptions& options) {
  const detail::ImpactScales scale = detail::impactScales(system);
  ImpactResult result;
  result.model = ImpactModelKind::Algebraic;
  result.mu = options.mu;
  result.V2_minus = system.V_minus.tail<2>();
  // Built once: the behaviours and the kinds of their slacks (for the normalisation).
  static const std::vector<ImpactBehaviour> behaviours = allImpactBehaviours();
  static const std::vector<std::vector<SlackInfo>> infos = [] {
    std::vector<std::vector<SlackInfo>> out;
    for (ImpactBehaviour b : allImpactBehaviours()) out.push_back(impactSlacks(b));
    return out;
  }();
  for (std::size_t k = 0; k < behaviours.size(); ++k) {
    const ImpactBehaviour b = behaviours[k];
    // Only the impulses and foot velocities decide consistency; Ẋ⁺ and the energy are
    // computed for the consistent behaviours alone (completeSolution).
    Matrix4S<double> M;
    Vector4S<double> r;
    impactEqualities(system, b, options.mu, M, r);
    const Eigen::Vector4d I = M.partialPivLu().solve(r);
    if (!I.allFinite()) continue;  // singular equality set: no solution of this kind
    const Eigen::VectorXd slacks =
        impactSlackValues<double>(I, system.V_minus + system.W * I, b, options.mu);
    bool consistent = true, boundary = false;
    for (Eigen::Index i = 0; i < slacks.size(); ++i) {
      const double unit = infos[k][static_cast<std::size_t>(i)].kind == SlackKind::Velocity
                              ? scale.speed
                              : scale.impulse;
      const double x = slacks(i) / unit;
      consistent = consistent && x >= -options.tolerance;
      boundary = boundary || std::abs(x) <= options.tolerance;
    }
    if (!consistent) continue;
    ImpactSolution s;
    s.behaviour = b;
    s.boundary = boundary;
    detail::completeSolution(system, I, options, s);
    s.phases.push_back({b, I(3)});
    detail::addDistinctSolution(result.solutions, std::move(s), options.tolerance * scale.impulse,
                                   options.outcome_tolerance);
  }
  result.status = detail::statusOf(result.solutions, options.tolerance * scale.impulse,
                                   options.outcome_tolerance);
  return result;
}

}  // namespace gaitopt
