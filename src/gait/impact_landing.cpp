#include "gaitopt/gait/impact_landing.hpp"

#include <algorithm>
#include <string>

#include "gaitopt/impact/solve_impact.hpp"

namespace gaitopt {

ImpactBehaviour landingBehaviour(Landing landing) {
  return landing == Landing::ImpactDoubleSupport
             ? ImpactBehaviour{Foot1Behaviour::Stick, Foot2Behaviour::Stick}
             : ImpactBehaviour{Foot1Behaviour::Lift, Foot2Behaviour::Stick};
}

int landingImpactSlackCount(Landing landing) {
  return static_cast<int>(impactSlacks(landingBehaviour(landing)).size());
}

LandingReport landingReport(const LandingImpact<double>& li, Landing landing,
                            double alphadot_minus) {
  const double s = -alphadot_minus;
  LandingReport r;
  r.behaviour = landingBehaviour(landing);
  r.X = li.X;
  r.Xd_minus = li.Xd_minus * s;
  r.Xd_plus = li.unit.Xd_plus * s;
  r.v2_minus = li.v2_minus * s;
  r.impulse1 = li.unit.impulse1 * s;
  r.impulse2 = li.unit.impulse2 * s;
  r.energy_loss = li.unit.energy_loss * s * s;
  r.alphadot_minus = alphadot_minus;
  r.alphadot_plus = li.rate_ratio * alphadot_minus;
  return r;
}

LandingSolutions landingSolutions(const Model& model, const LandingReport& report, double mu) {
  ImpactOptions options;
  options.mu = mu;
  const ImpactSystem<double> sys = impactSystem(model, report.X, report.Xd_minus);
  const ImpactResult algebraic = solveAlgebraicImpact(sys, options);
  const ImpactResult differential = solveDifferentialImpact(sys, options);
  LandingSolutions r;
  r.status = toString(algebraic.status);
  r.count = static_cast<int>(algebraic.solutions.size());
  for (const ImpactSolution& s : algebraic.solutions)
    r.required_found = r.required_found || s.behaviour == report.behaviour;
  r.differential_status = toString(differential.status);
  r.differential_count = static_cast<int>(differential.solutions.size());
  for (const ImpactSolution& s : differential.solutions)
    r.differential_difference =
        std::max(r.differential_difference, (s.Xd_plus - report.Xd_plus).cwiseAbs().maxCoeff());
  return r;
}

const char* afterImpactName(Landing landing) {
  return landing == Landing::ImpactSingleSupport ? "single_support" : "double_support";
}

}  // namespace gaitopt
