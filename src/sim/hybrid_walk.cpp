#include "gaitopt/sim/hybrid_walk.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "gaitopt/gait/ds_force_distribution.hpp"
#include "gaitopt/gait/leg_geometry.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/forward_dynamics.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"

namespace gaitopt {
namespace {

constexpr int kStateSize = 12;  // q, q̇, ∫ωᵀΓ* dt, ∫ωᵀ(Γ* − Γ) dt
constexpr int kRoots = 5;
constexpr double kGroundTolerance = 1e-6;  // [m] swing foot below the ground: early touchdown
constexpr double kFallHipHeight = 0.3;     // [m]

// SS input–output linearisation: Γ with B A⁻¹ D_Γ Γ = ÿ* + δ_d'' α̇² + B A⁻¹ (C + G), where
// y = δ − δ_d(α), ẏ = B q̇, B = [−δ_d'(α) | I], ÿ* = −ω² y − 2ω ẏ.
Vec4 ssControl(const Model& c, const GaitMotion<double>& mo, double w, const Vec5& q,
               const Vec5& qd, Vec4& y) {
  const PinnedTerms<double> t = pinnedTerms(c, q, qd);
  Eigen::Matrix<double, 4, 5> B = Eigen::Matrix<double, 4, 5>::Zero();
  Vec4 curvature, yd;
  for (int j = 0; j < 4; ++j) {
    const PolyValue<double> v = mo.ss_path[j](q(0));
    B(j, 0) = -v.first;
    B(j, j + 1) = 1.0;
    y(j) = q(j + 1) - v.value;
    curvature(j) = v.second * qd(0) * qd(0);
  }
  yd = B * qd;
  const Eigen::LDLT<Mat5> A(t.A);
  const Eigen::Matrix<double, 5, 4> Ainv_D = A.solve(c.D_Gamma);
  const Vec5 Ainv_CG = A.solve(Vec5(t.C + t.G));
  const Eigen::Matrix4d Lg = B * Ainv_D;
  const Vec4 target = -w * w * y - 2.0 * w * yd;
  const Vec4 gamma = Lg.partialPivLu().solve(Vec4(target + curvature + B * Ainv_CG));
  return gamma + frictionTorque(c, jointSpeeds(qd), SignMode::Smooth);
}

// DS: (α, δ1, δ2) track α_r(t) and δ_d(α_r(t)); δ3, δ4 accelerations from the closed chain
// (1.35); R2x, the fourth input, of least Γ*ᵀΓ* within both friction cones (the 1-D QP
// (3.68)–(3.70) of the gait's force split).
Vec4 dsControl(const Model& c, const GaitMotion<double>& mo, const LocalPolynomial<double>& ar,
               double w, double mu, double t, const Vec5& q, const Vec5& qd, Vec4& err) {
  const PolyValue<double> a = ar(t);
  const PolyValue<double> d1 = mo.ds_delta1(a.value), d2 = mo.ds_delta2(a.value);
  const Eigen::Vector3d p(a.value, d1.value, d2.value);
  const Eigen::Vector3d pd(a.first, d1.first * a.first, d2.first * a.first);
  const Eigen::Vector3d pdd(a.second, d1.second * a.first * a.first + d1.first * a.second,
                            d2.second * a.first * a.first + d2.first * a.second);
  const Eigen::Vector3d e = p - q.head<3>(), ed = pd - qd.head<3>();
  err << e, 0.0;
  const Eigen::Vector3d acc = pdd + w * w * e + 2.0 * w * ed;
  const ChainState<double> st = chainState(c, q, qd);
  const Matrix25<double> D2 = chainPointJacobian(c, c.pinned.foot2, st);
  const Vec2 H2 = chainPointBias(c.pinned.foot2, st);
  const Vec2 a34 = -D2.rightCols<2>().inverse() * (D2.leftCols<3>() * acc + H2);
  Vec5 qdd;
  qdd << acc, a34;
  const DoubleSupportAffine<double> aff = doubleSupportAffine(c, q, qd, qdd, SignMode::Smooth);
  const double M = c.total_mass;
  const double R1z0 = M * (aff.com_acceleration(1) + c.gravity) - aff.R2z0;  // (3.59)
  const DsBounds<double> bounds =
      r2xBounds(R1z0, aff.R2z0, M * aff.com_acceleration(0), mu, kBranchFree);  // (3.66)
  return aff.J - aff.K * r2xMinTorque(aff.J, aff.K, bounds, kBranchFree).r2x;  // (3.68)–(3.70)
}

// Plant in DS: A q̈ − D2ᵀ R2 = D_Γ Γ − C − G and D2 q̈ + H2 = 0.
void dsPlant(const Model& p, const Vec5& q, const Vec5& qd, const Vec4& gamma, Vec5& qdd,
             Vec2& R2) {
  const PinnedTerms<double> t = pinnedTerms(p, q, qd);
  Eigen::Matrix<double, 7, 7> K = Eigen::Matrix<double, 7, 7>::Zero();
  K.topLeftCorner<5, 5>() = t.A;
  K.topRightCorner<5, 2>() = -t.D2.transpose();
  K.bottomLeftCorner<2, 5>() = t.D2;
  Eigen::Matrix<double, 7, 1> rhs;
  rhs << p.D_Gamma * gamma - t.C - t.G, -t.H2;
  const Eigen::Matrix<double, 7, 1> x = K.partialPivLu().solve(rhs);
  qdd = x.head<5>();
  R2 = x.tail<2>();
}

class Walker {
 public:
  Walker(const GaitEvaluation<double>& e, const Model& c, const Model& p, const WalkRequest& r,
         const TouchdownMap& td)
      : mo_(e.motion), c_(c), p_(p), req_(r), td_(td),
        cv_(kStateSize, [this](double t, const Eigen::VectorXd& y, Eigen::VectorXd& f) { rhs(t, y, f); },
            kRoots, [this](double t, const Eigen::VectorXd& y, Eigen::VectorXd& g) { roots(t, y, g); },
            r.tolerances) {}

  WalkResult run();

 private:
  const GaitMotion<double>& mo_;
  const Model& c_;
  const Model& p_;
  const WalkRequest& req_;
  const TouchdownMap& td_;
  CvodeIntegrator cv_;
  bool ss_ = true;
  double t_end_ds_ = 0.0;
  LocalPolynomial<double> alpha_ref_;
  WalkResult out_;

  ClosedLoopEval evaluate(double t, const Eigen::VectorXd& y) const {
    return evaluateClosedLoop(mo_, c_, p_, req_, ss_ ? nullptr : &alpha_ref_, t, y.head<5>(),
                              y.segment<5>(5));
  }

  void rhs(double t, const Eigen::VectorXd& y, Eigen::VectorXd& f) const {
    const ClosedLoopEval e = evaluate(t, y);
    const Vec4 w = jointSpeeds(Vec5(y.segment<5>(5)));
    f.resize(kStateSize);
    f << y.segment<5>(5), e.qdd, w.dot(e.gamma_star), w.dot(e.friction);
  }

  void roots(double t, const Eigen::VectorXd& y, Eigen::VectorXd& g) const {
    const ClosedLoopEval e = evaluate(t, y);
    const Vec5 q = y.head<5>();
    const ChainState<double> st = chainState(p_, q, Vec5(y.segment<5>(5)));
    g.resize(kRoots);
    if (ss_) {
      g << q(0) - mo_.alpha_fSS, chainPoint(p_.pinned.foot2, st)(1) + kGroundTolerance, e.R1(1),
          chainPoint(p_.pinned.hip, st)(1) - kFallHipHeight, -y(5);
    } else {
      g << t_end_ds_ - t, e.R1(1), e.R2(1), 1.0, 1.0;
    }
  }

  void record(double t, const Eigen::VectorXd& y, int step) {
    const ClosedLoopEval e = evaluate(t, y);
    out_.samples.push_back({t, step, ss_, y.head<5>(), y.segment<5>(5), e.qdd, e.gamma_star,
                            e.error, e.R1, e.R2});
    WalkStep& s = out_.steps.back();
    if (ss_) s.max_output_error = std::max(s.max_output_error, e.error.cwiseAbs().maxCoeff());
    s.min_normal_force = std::min({s.min_normal_force, e.R1(1), ss_ ? e.R1(1) : e.R2(1)});
  }

  // Integrates the current phase to its end event, recording samples; returns the event.
  CvodeIntegrator::Result phase(double t0, const Eigen::VectorXd& y0, int step) {
    cv_.reset(t0, y0);
    record(t0, y0, step);
    // Events are falling crossings; a force or fall condition already violated at the phase
    // start is one too (the swing foot starts on the ground at lift-off: not checked).
    Eigen::VectorXd g;
    roots(t0, y0, g);
    for (int i = 0; i < kRoots; ++i)
      if (g(i) < 0.0 && !(ss_ && i == 1)) return {t0, y0, i};
    const double dt = 1.0 / req_.sample_rate;
    double next = (std::floor(t0 / dt) + 1.0) * dt;
    for (;;) {
      CvodeIntegrator::Result r = cv_.advance(ss_ ? next : std::min(next, t_end_ds_));
      record(r.t, r.y, step);
      if (r.root >= 0 || (!ss_ && r.t >= t_end_ds_)) return r;
      next += dt;
    }
  }

  bool fail(WalkOutcome o, const std::string& msg) {
    out_.outcome = o;
    out_.message = msg;
    return false;
  }

  bool singleSupport(double& t, Eigen::VectorXd& y, int k);
  bool doubleSupport(double& t, Eigen::VectorXd& y, int k);
};

bool Walker::singleSupport(double& t, Eigen::VectorXd& y, int k) {
  ss_ = true;
  WalkStep s;
  s.step = k;
  s.t_start = t;
  s.alphad_start = y(5);
  s.energy_start = pinnedEnergy(p_, y.head<5>(), y.segment<5>(5));
  s.min_normal_force = std::numeric_limits<double>::infinity();
  out_.steps.push_back(s);
  y(10) = y(11) = 0.0;
  const CvodeIntegrator::Result r = phase(t, y, k);
  t = r.t;
  y = r.y;
  WalkStep& st = out_.steps.back();
  const std::string at = "step " + std::to_string(k) + " at t = " + std::to_string(t) + " s";
  if (r.root == 1) return fail(WalkOutcome::EarlyTouchdown, "swing foot below the ground, " + at);
  if (r.root == 2) return fail(WalkOutcome::StanceLiftOff, "stance foot normal force < 0, " + at);
  if (r.root == 3 || r.root == 4) return fail(WalkOutcome::Fell, "fell back or down, " + at);
  const Vec5 q = y.head<5>(), qd = y.segment<5>(5);
  st.t_touchdown = t;
  st.touchdown_event_residual = std::abs(q(0) - mo_.alpha_fSS) / std::abs(qd(0));
  st.touchdown_foot_speed = (pinnedTerms(p_, q, qd).D2 * qd).norm();
  st.energy_touchdown = pinnedEnergy(p_, q, qd);
  st.motor_work = y(10);
  st.friction_loss = y(11);
  Vec5 qp, qdp;
  std::string why;
  if (!td_(p_, q, qd, qp, qdp, why)) return fail(WalkOutcome::ImpactUnavailable, why + ", " + at);
  y.head<5>() = qp;
  y.segment<5>(5) = qdp;
  return true;
}

bool Walker::doubleSupport(double& t, Eigen::VectorXd& y, int k) {
  ss_ = false;
  t_end_ds_ = t + mo_.T_DS;
  alpha_ref_ = dsAlphaReference(mo_, t, y(0), y(5));
  const CvodeIntegrator::Result r = phase(t, y, k);
  t = r.t;
  y = r.y;
  out_.steps.back().t_liftoff = t;
  if (r.root == 1 || r.root == 2)
    return fail(WalkOutcome::StanceLiftOff,
                "a foot's normal force < 0 in double support, step " + std::to_string(k));
  return true;
}

WalkResult Walker::run() {
  Eigen::VectorXd y(kStateSize);
  const Vec5 q0 = mo_.q_iSS + req_.dq0;
  Vec5 qs;  // q*(α) = ∂q/∂α on the virtual constraints
  qs(0) = 1.0;
  for (int j = 0; j < 4; ++j) qs(j + 1) = mo_.ss_path[j](q0(0)).first;
  y << q0, qs * (mo_.alphadot_iSS + req_.dalphad0), 0.0, 0.0;
  if (req_.use_initial_state) y << req_.q_init, req_.qd_init, 0.0, 0.0;
  double t = 0.0;
  for (int k = 0; k < req_.steps; ++k) {
    if (!singleSupport(t, y, k) || !doubleSupport(t, y, k)) break;
    out_.q_end = y.head<5>();
    out_.qd_end = y.segment<5>(5);
  }
  return out_;
}

}  // namespace

ClosedLoopEval evaluateClosedLoop(const GaitMotion<double>& mo, const Model& c, const Model& p,
                                  const WalkRequest& req,
                                  const LocalPolynomial<double>* ds_alpha_reference, double t,
                                  const Vec5& q, const Vec5& qd) {
  ClosedLoopEval e;
  e.gamma_star = ds_alpha_reference
                     ? dsControl(c, mo, *ds_alpha_reference, req.bandwidth,
                                 req.friction_coefficient, t, q, qd, e.error)
                     : ssControl(c, mo, req.bandwidth, q, qd, e.error);
  e.friction = frictionTorque(p, jointSpeeds(qd), SignMode::Smooth);
  if (ds_alpha_reference) {
    dsPlant(p, q, qd, e.gamma_star - e.friction, e.qdd, e.R2);
  } else {
    e.qdd = forwardDynamicsSS(p, q, qd, e.gamma_star, SignMode::Smooth);
    e.R2.setZero();
  }
  const Vec2 acc = pinnedComAcceleration(p, q, qd, e.qdd);
  e.R1 = Vec2(p.total_mass * acc(0), p.total_mass * (acc(1) + p.gravity)) - e.R2;
  return e;
}

// DS control of α: from the touchdown state to the cycle's (α_fDS, α̇_iSS) at lift-off.
LocalPolynomial<double> dsAlphaReference(const GaitMotion<double>& mo, double t_touchdown,
                                         double alpha, double alphad) {
  return cubicHermite(t_touchdown, alpha, alphad, t_touchdown + mo.T_DS,
                      mo.ds_alpha(mo.T_DS).value, mo.alphadot_iSS);
}

TouchdownMap impulseFreeTouchdown(double speed_tol) {
  return [speed_tol](const Model& plant, const Vec5& q, const Vec5& qd, Vec5& qp, Vec5& qdp,
                     std::string& why) {
    const double speed = (pinnedTerms(plant, q, qd).D2 * qd).norm();
    if (speed > speed_tol) {
      why = "touchdown with non-zero velocity " + std::to_string(speed) +
            " m/s: impact model not available";
      return false;
    }
    qp = exchangeLegs(q);  // (3.22)
    qdp = exchangeLegVelocities(qd);  // (3.23)
    return true;
  };
}

const char* outcomeName(WalkOutcome o) {
  switch (o) {
    case WalkOutcome::Completed: return "completed";
    case WalkOutcome::ImpactUnavailable: return "impact_model_unavailable";
    case WalkOutcome::EarlyTouchdown: return "early_touchdown";
    case WalkOutcome::StanceLiftOff: return "stance_lift_off";
    case WalkOutcome::Fell: return "fell";
  }
  return "unknown";
}

WalkResult simulateWalk(const GaitEvaluation<double>& e, const Model& controller,
                        const Model& plant, const WalkRequest& request,
                        const TouchdownMap& touchdown) {
  Walker w(e, controller, plant, request, touchdown);
  return w.run();
}

}  // namespace gaitopt
