#include "gaitopt/sim/impact_touchdown.hpp"

#include <Eigen/Dense>
#include <cmath>
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

TouchdownMap doubleSupportTouchdown(double mu, bool rear_lift_starts_ss, double impact_duration,
                                    double speed_tol) {
  ImpactOptions io;
  io.mu = mu;
  const TouchdownMap rigid =
      impactTouchdown(ImpactModelKind::Algebraic, io, !rear_lift_starts_ss, speed_tol);
  return [=](const Model& plant, const Vec5& q, const Vec5& qd) {
    const PinnedTerms<double> t = pinnedTerms(plant, q, qd);
    // Foot 1 stays pinned; foot 2 stops: A Δq̇ = D2ᵀ I2 with D2 q̇⁺ = 0.
    const Eigen::LDLT<Mat5> A(t.A);
    const Eigen::Matrix<double, 5, 2> AinvDt = A.solve(t.D2.transpose());
    const Vec2 I2 = -(t.D2 * AinvDt).ldlt().solve(t.D2 * qd);
    const Vec5 qd_plus = qd + AinvDt * I2;
    // Foot 1's impulse closes the momentum balance M Δv_G = I1 + I2.
    const Vec2 I1 =
        plant.total_mass * (pinnedTerms(plant, q, qd_plus).com_velocity - t.com_velocity) - I2;
    const double preload = plant.total_mass * plant.gravity * impact_duration;
    // Below speed_tol the impulses are round-off: always held (the map stays energy-exact,
    // where relabelling alone would leave the foot's residual velocity in the new stance).
    const bool admissible = (t.D2 * qd).norm() <= speed_tol ||
                            (I2(1) >= 0.0 && std::abs(I2(0)) <= mu * I2(1) &&
                            I1(1) + preload >= 0.0 && std::abs(I1(0)) <= mu * (I1(1) + preload));
    if (!admissible) return rigid(plant, q, qd);
    TouchdownResult r;
    r.ok = true;
    r.q_plus = exchangeLegs(q);                // (3.22)
    r.qd_plus = exchangeLegVelocities(qd_plus);  // (3.23)
    r.energy_loss = 0.5 * (qd.dot(t.A * qd) - qd_plus.dot(t.A * qd_plus));
    r.impulse1 = I1;
    r.impulse2 = I2;
    r.behaviour = "held/stick";
    return r;
  };
}

std::string resolvedImpactModel(const GaitOptions& o, const std::string& model) {
  if (model != "auto") return model;
  if (o.parameterisation.landsWithImpact()) return "algebraic";
  return o.parameterisation.hasDoubleSupport() ? "double_support" : "none";
}

TouchdownMap gaitTouchdown(const GaitOptions& o, const std::string& model, double ground_mu) {
  const std::string m = resolvedImpactModel(o, model);
  if (m == "none") return impulseFreeTouchdown(1e-6, o.parameterisation.hasDoubleSupport());
  if (m == "double_support") return doubleSupportTouchdown(ground_mu, false);
  if (m != "algebraic" && m != "differential")
    throw std::invalid_argument("unknown impact model '" + model + "'");
  ImpactOptions io;
  io.mu = ground_mu;
  return impactTouchdown(
      m == "algebraic" ? ImpactModelKind::Algebraic : ImpactModelKind::Differential, io,
      o.parameterisation.hasDoubleSupport());
}

}  // namespace gaitopt
