#include "gaitopt/gait/impact_landing.hpp"

#include <string>

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
  // A slack counts as satisfied down to round-off of the impulses and velocities involved.
  const double tol = 1e-9 * (1.0 + report.Xd_minus.norm()) * model.total_mass;
  const ImpactSystem<double> sys = impactSystem(model, report.X, report.Xd_minus);
  LandingSolutions r;
  for (ImpactBehaviour b : allImpactBehaviours()) {
    const ImpactOutcome<double> o = algebraicImpact(sys, b, mu);
    if (!o.Xd_plus.allFinite() || o.slacks.minCoeff() < -tol) continue;
    ++r.count;
    r.required_found = r.required_found || b == report.behaviour;
  }
  r.status = r.count == 0 ? "inconsistent" : r.count > 1 ? "indeterminate" : "unique";
  return r;
}

const char* afterImpactName(Landing landing) {
  return landing == Landing::ImpactSingleSupport ? "single_support" : "double_support";
}

}  // namespace gaitopt
