// Algebraic impact: the 12 behaviours of Appendix C enumerated, every consistent one kept.
#include <cmath>

#include "gaitopt/impact/impact_solver.hpp"

namespace gaitopt {

ImpactResult solveAlgebraicImpact(const ImpactSystem<double>& system, const ImpactOptions& options) {
  const detail::ImpactScales scale = detail::impactScales(system);
  ImpactResult result;
  result.model = ImpactModelKind::Algebraic;
  result.mu = options.mu;
  result.V2_minus = system.V_minus.tail<2>();
  for (ImpactBehaviour b : allImpactBehaviours()) {
    const ImpactOutcome<double> o = algebraicImpact(system, b, options.mu);
    if (!o.Xd_plus.allFinite()) continue;  // singular equality set: no solution of this kind
    const std::vector<SlackInfo> info = impactSlacks(b);
    bool consistent = true, boundary = false;
    for (Eigen::Index i = 0; i < o.slacks.size(); ++i) {
      const double unit = info[static_cast<std::size_t>(i)].kind == SlackKind::Velocity
                              ? scale.speed
                              : scale.impulse;
      const double x = o.slacks(i) / unit;
      consistent = consistent && x >= -options.tolerance;
      boundary = boundary || std::abs(x) <= options.tolerance;
    }
    if (!consistent) continue;
    ImpactSolution s;
    s.behaviour = b;
    s.boundary = boundary;
    Eigen::Vector4d I;
    I << o.impulse1, o.impulse2;
    detail::completeSolution(system, I, options, s);
    s.phases.push_back({b, o.impulse2(1)});
    detail::addDistinctSolution(result.solutions, std::move(s), options.tolerance * scale.impulse,
                                   options.outcome_tolerance);
  }
  result.status = detail::statusOf(result.solutions, options.tolerance * scale.impulse,
                                   options.outcome_tolerance);
  return result;
}

}  // namespace gaitopt
