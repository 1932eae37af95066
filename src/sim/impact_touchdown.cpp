#include "gaitopt/sim/impact_touchdown.hpp"

#include <stdexcept>

#include "gaitopt/gait/leg_geometry.hpp"
#include "gaitopt/impact/impact_map.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"

namespace gaitopt {
namespace {

TouchdownResult failed(WalkOutcome o, const std::string& why) {
  TouchdownResult r;
  r.failure = o;
  r.why = why;
  return r;
}

// The post-impact state of one solution, or the outcome that ends the walk.
TouchdownResult fromSolution(const ImpactSolution& s, const Vec5& q, bool double_support_gait) {
  const std::string label = behaviourLabel(s.contact);
  const bool foot1_slides =
      s.contact.foot1 == Foot1Behaviour::SlipPlus || s.contact.foot1 == Foot1Behaviour::SlipMinus;
  if (s.contact.foot2 != Foot2Behaviour::Stick || foot1_slides)
    return failed(WalkOutcome::Slipped, "a foot slides after the impact (" + label + ")");
  if (s.contact.foot1 == Foot1Behaviour::Lift && double_support_gait)
    return failed(WalkOutcome::RearFootLift, "the impact lifts the rear foot (" + label +
                                                 "), the gait needs a double support");
  TouchdownResult r;
  r.ok = true;
  r.q_plus = exchangeLegs(q);                                    // (3.22)
  r.qd_plus = exchangeLegVelocities(Vec5(s.Xd_plus.head<5>()));  // (3.23)
  r.double_support_follows = s.contact.foot1 != Foot1Behaviour::Lift;
  r.energy_loss = s.energy_loss;
  r.impulse1 = s.impulse1;
  r.impulse2 = s.impulse2;
  r.behaviour = label;
  return r;
}

}  // namespace

TouchdownMap impactTouchdown(ImpactModelKind kind, const ImpactOptions& options,
                             bool double_support_gait, double speed_tol) {
  const TouchdownMap impulse_free = impulseFreeTouchdown(speed_tol, double_support_gait);
  return [=](const Model& plant, const Vec5& q, const Vec5& qd) {
    if ((pinnedTerms(plant, q, qd).D2 * qd).norm() <= speed_tol) return impulse_free(plant, q, qd);
    const ImpactResult res = solveImpactFromPinned(plant, q, qd, kind, options);
    if (res.status == ImpactStatus::Inconsistent || res.status == ImpactStatus::Indeterminate)
      return failed(WalkOutcome::ImpactUnavailable,
                    std::string(toString(kind)) + " impact " + toString(res.status) + " (" +
                        std::to_string(res.solutions.size()) + " solutions)");
    return fromSolution(res.solutions.front(), q, double_support_gait);
  };
}

std::string resolvedImpactModel(const GaitOptions& o, const std::string& model) {
  if (model != "auto") return model;
  return o.parameterisation.landsWithImpact() ? "algebraic" : "none";
}

TouchdownMap gaitTouchdown(const GaitOptions& o, const std::string& model, double ground_mu) {
  const std::string m = resolvedImpactModel(o, model);
  if (m == "none") return impulseFreeTouchdown(1e-6, o.parameterisation.hasDoubleSupport());
  if (m != "algebraic" && m != "differential")
    throw std::invalid_argument("unknown impact model '" + model + "'");
  ImpactOptions io;
  io.mu = ground_mu;
  return impactTouchdown(
      m == "algebraic" ? ImpactModelKind::Algebraic : ImpactModelKind::Differential, io,
      o.parameterisation.hasDoubleSupport());
}

}  // namespace gaitopt
