#include "gaitopt/sim/poincare_sensitivity.hpp"

#include <stdexcept>

namespace gaitopt {
namespace {

constexpr double kTouchdownMapStep = 1e-7;  // central differences of the touchdown map
constexpr double kMaxStepTime = 10.0;       // [s] SS without touchdown: not a step

// (q̇, q̈) of the closed loop (sim/closed_loop.hpp, the simulation's own right-hand side).
Eigen::VectorXd closedLoopField(const ClosedLoop& s, bool single_support, const DsReference& ds,
                                double t, const Eigen::VectorXd& x) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(x.size());
  f.head<5>() = x.segment<5>(5);
  f.segment<5>(5) =
      evaluateClosedLoop(s, single_support, ds, t, x.head<5>(), x.segment<5>(5)).qdd;
  return f;
}

TouchdownResult touchdownAt(const TouchdownMap& td, const Model& plant, const Eigen::VectorXd& x) {
  const TouchdownResult r = td(plant, x.head<5>(), x.segment<5>(5));
  if (!r.ok) throw std::runtime_error("walking step sensitivity: " + r.why);
  return r;
}

Eigen::VectorXd applyTouchdown(const TouchdownMap& td, const Model& plant,
                               const Eigen::VectorXd& x) {
  const TouchdownResult r = touchdownAt(td, plant, x);
  Eigen::VectorXd y(10);
  y << r.q_plus, r.qd_plus;
  return y;
}

// The DS, timed from the touchdown, on z = (q, q̇, α⁺, α̇⁺): the last two fix the cubic α
// reference (dsReference) and so carry its dependence on the touchdown state.
PhaseEnd doubleSupportWithSensitivity(const ClosedLoop& s, const SensitiveState& plus,
                                      const CvodeTolerances& tol) {
  const GaitMotion<double>& mo = s.motion;
  HybridPhase ds;
  ds.field = [&s](double t, const Eigen::VectorXd& z, Eigen::VectorXd& f) {
    Vec5 q = z.head<5>(), qd = z.segment<5>(5);
    q(0) = z(10);
    qd(0) = z(11);
    f = closedLoopField(s, false, dsReference(s, 0.0, q, qd), t, z);
  };
  const bool optimal = s.options.ds_control == DsAlphaControl::TimeOptimal;
  const double alpha_fDS = mo.ds_alpha(mo.T_DS).value;
  if (optimal) ds.event = [alpha_fDS](const Eigen::VectorXd& z) { return z(0) - alpha_fDS; };
  SensitiveState z0;
  z0.x.resize(12);
  z0.x << plus.x, plus.x(0), plus.x(5);
  z0.S.resize(12, plus.S.cols());
  if (plus.S.cols() > 0)  // (no sensitivities: a 0-column block of a null pointer is UB)
    z0.S << plus.S, plus.S.row(0), plus.S.row(5);
  const double t_end = dsReference(s, 0.0, plus.x.head<5>(), plus.x.segment<5>(5)).t_end;
  const PhaseEnd lift = flowWithSensitivity(ds, z0, t_end, tol);
  if (optimal && !lift.event)
    throw std::runtime_error("walking step sensitivity: alpha did not reach alpha_fDS");
  return lift;
}

}  // namespace

ClosedLoop walkingClosedLoop(const GaitMotion<double>& mo, const Model& c, const Model& p,
                             const WalkRequest& req) {
  return {mo, c, p, closedLoopOptions(req)};
}

HybridPhase walkingSingleSupport(const ClosedLoop& s, double alpha_end, bool at_touchdown) {
  HybridPhase ss;
  ss.field = [&s](double t, const Eigen::VectorXd& y, Eigen::VectorXd& f) {
    f = closedLoopField(s, true, DsReference{}, t, y);
  };
  if (at_touchdown) {
    ss.event = [&s](const Eigen::VectorXd& y) { return touchdownEvent(s, y.head<5>()); };
  } else {
    ss.event = [alpha_end](const Eigen::VectorXd& y) { return y(0) - alpha_end; };
  }
  return ss;
}

StepSensitivity walkingStepSensitivity(const GaitEvaluation<double>& e, const Model& c,
                                       const Model& p, const WalkRequest& req,
                                       const Eigen::VectorXd& x, const TouchdownMap& td,
                                       bool with_jacobian) {
  const ClosedLoop s = walkingClosedLoop(e.motion, c, p, req);
  const HybridPhase ss = walkingSingleSupport(s, e.motion.alpha_fSS, true);
  const PhaseEnd touch =
      flowWithSensitivity(ss, {0.0, x, Eigen::MatrixXd::Identity(10, with_jacobian ? 10 : 0)},
                          kMaxStepTime, req.tolerances);
  if (!touch.event) throw std::runtime_error("walking step sensitivity: no touchdown");
  const TouchdownResult r = touchdownAt(td, p, touch.state.x);
  SensitiveState plus{0.0, Eigen::VectorXd(10), touch.state.S};
  plus.x << r.q_plus, r.qd_plus;
  if (with_jacobian)
    plus.S = centralJacobian(
                 [&](const Eigen::VectorXd& y) { return applyTouchdown(td, p, y); },
                 touch.state.x, kTouchdownMapStep) *
             touch.state.S;
  if (!r.double_support_follows) return {plus.x, plus.S};
  const PhaseEnd lift = doubleSupportWithSensitivity(s, plus, req.tolerances);
  return {lift.state.x.head(10), lift.state.S.topRows(10)};
}

PoincareLinearisation linearisePoincareBySensitivity(const GaitEvaluation<double>& e,
                                                     const Model& c, const Model& p,
                                                     const WalkRequest& req,
                                                     const Eigen::VectorXd& x,
                                                     const TouchdownMap& td) {
  const StepSensitivity s = walkingStepSensitivity(e, c, p, req, x, td);
  PoincareLinearisation L = analyseJacobian(s.jacobian);
  L.fixed_point_residual = (s.x_next - x).lpNorm<Eigen::Infinity>();
  return L;
}

}  // namespace gaitopt
