#include "gaitopt/sim/poincare_sensitivity.hpp"

#include <stdexcept>

namespace gaitopt {
namespace {

constexpr double kTouchdownMapStep = 1e-7;  // central differences of the touchdown map
constexpr double kMaxStepTime = 10.0;       // [s] SS without touchdown: not a step

Eigen::VectorXd closedLoopField(const GaitMotion<double>& mo, const Model& c, const Model& p,
                                const WalkRequest& req, const LocalPolynomial<double>* ref,
                                double t, const Eigen::VectorXd& x) {
  Eigen::VectorXd f(x.size());
  f.setZero();
  f.head<5>() = x.segment<5>(5);
  f.segment<5>(5) =
      evaluateClosedLoop(mo, c, p, req, ref, t, x.head<5>(), x.segment<5>(5)).qdd;
  return f;
}

Eigen::VectorXd applyTouchdown(const TouchdownMap& td, const Model& plant,
                               const Eigen::VectorXd& x) {
  Vec5 qp, qdp;
  std::string why;
  if (!td(plant, x.head<5>(), x.segment<5>(5), qp, qdp, why))
    throw std::runtime_error("walking step sensitivity: " + why);
  Eigen::VectorXd y(10);
  y << qp, qdp;
  return y;
}

}  // namespace

HybridPhase walkingSingleSupport(const GaitMotion<double>& mo, const Model& c, const Model& p,
                                 const WalkRequest& req, double alpha_end) {
  HybridPhase ss;
  ss.field = [&mo, &c, &p, req](double t, const Eigen::VectorXd& y, Eigen::VectorXd& f) {
    f = closedLoopField(mo, c, p, req, nullptr, t, y);
  };
  ss.event = [alpha_end](const Eigen::VectorXd& y) { return y(0) - alpha_end; };
  return ss;
}

StepSensitivity walkingStepSensitivity(const GaitEvaluation<double>& e, const Model& c,
                                       const Model& p, const WalkRequest& req,
                                       const Eigen::VectorXd& x, const TouchdownMap& td,
                                       bool with_jacobian) {
  const GaitMotion<double>& mo = e.motion;
  const HybridPhase ss = walkingSingleSupport(mo, c, p, req, mo.alpha_fSS);
  const PhaseEnd touch =
      flowWithSensitivity(ss, {0.0, x, Eigen::MatrixXd::Identity(10, with_jacobian ? 10 : 0)},
                          kMaxStepTime,
                          req.tolerances);
  if (!touch.event) throw std::runtime_error("walking step sensitivity: no touchdown");
  const Eigen::VectorXd x_plus = applyTouchdown(td, p, touch.state.x);
  const Eigen::MatrixXd S_plus =
      with_jacobian
          ? Eigen::MatrixXd(centralJacobian(
                                [&](const Eigen::VectorXd& y) { return applyTouchdown(td, p, y); },
                                touch.state.x, kTouchdownMapStep) *
                            touch.state.S)
          : touch.state.S;
  // DS timed from the touchdown; z = (q, q̇, α⁺, α̇⁺), the last two fixing α_r.
  HybridPhase ds;
  ds.field = [&](double t, const Eigen::VectorXd& z, Eigen::VectorXd& f) {
    const LocalPolynomial<double> ref = dsAlphaReference(mo, 0.0, z(10), z(11));
    f = closedLoopField(mo, c, p, req, &ref, t, z);
  };
  SensitiveState z0;
  z0.x.resize(12);
  z0.x << x_plus, x_plus(0), x_plus(5);
  z0.S.resize(12, S_plus.cols());
  z0.S << S_plus, S_plus.row(0), S_plus.row(5);
  const PhaseEnd lift = flowWithSensitivity(ds, z0, mo.T_DS, req.tolerances);
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
