#include "gaitopt/sim/closed_loop.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

#include "gaitopt/gait/constraints/contact.hpp"
#include "gaitopt/gait/constraints/torque_envelope.hpp"
#include "gaitopt/gait/ds_force_distribution.hpp"
#include "gaitopt/gait/leg_geometry.hpp"
#include "gaitopt/math/small_qp.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/forward_dynamics.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"
#include "gaitopt/sim/control_constraints.hpp"
#include "gaitopt/sim/ds_acceleration_bounds.hpp"

namespace gaitopt {
namespace {

constexpr double kGroundTolerance = 1e-6;  // [m] swing foot below the ground: early touchdown
constexpr double kFallHipHeight = 0.3;     // [m]
// Weight of R2x [1/N²] against the DS output accelerations [1/(rad/s²)²] in (4.60): the thesis
// leaves R2x out of the objective (non-unique); a small weight keeps the least-torque choice
// unless the constraints need another.
constexpr double kR2xWeight = 1e-6;
// [N·m, N] a constraint row within this of its bound holds: optimised gaits ride on their
// torque limits and friction cones, which round-off must not count as a violation.
constexpr double kConstraintTolerance = 1e-8;
// Fraction of the plant's weight by which a contact constraint of the plant may be violated
// before it counts (|Rx| > μ Rz: slip; Rz < 0: lift-off): the optimised DS puts R2x on the
// cone of the gait's μ, and the projection (4.60) holds a normal force at 0 (round-off margin).
constexpr double kContactTolerance = 1e-7;

// Torques and reactions the controller's model predicts for the inputs v (SS: ÿ; DS: α̈, δ̈1,
// δ̈2, R2x); affine in v at a given state.
struct InputResponse {
  Vec4 gamma_star;
  Vec2 R1, R2;
};

// The contact constraints of the projection: friction cones of coefficient mu about the normal
// of the ground inclined by `slope`, normal forces of at least r_min ((4.2): the margin
// R_min > 0 that keeps a foot loaded).
struct ContactLimits {
  double mu, r_min, slope;
};

// Rows c(v) ≤ 0 of (4.51)–(4.54): torque envelope, normal forces ≥ R_min, friction cones.
Eigen::VectorXd constraintValues(const InputResponse& r, const Vec4& limit, const ContactLimits& k,
                                 bool double_support) {
  const Eigen::Rotation2Dd to_ground(-k.slope);
  return controlConstraintRows(r.gamma_star, limit, to_ground * r.R1, to_ground * r.R2,
                               double_support, k.mu, k.r_min);
}

struct Projected {
  Vec4 v;
  bool saturated = false, infeasible = false;
};

// (4.57), (4.60): the inputs closest to v_d (weights w) whose predicted torques and reactions
// satisfy the constraints; the contact rows are dropped when no input satisfies them all (the
// torque limits alone are always feasible: Γ* is an invertible affine function of v).
template <class Response>
Projected projectInputs(const Response& response, const Vec4& v_d, const Vec4& w, const Vec4& limit,
                        const ContactLimits& k, bool double_support) {
  const InputResponse r0 = response(v_d);
  const Eigen::VectorXd c0 = constraintValues(r0, limit, k, double_support);
  if (c0.maxCoeff() <= kConstraintTolerance) return {v_d};
  Eigen::MatrixXd G(c0.size(), 4);
  for (int i = 0; i < 4; ++i)  // exact columns: the response is affine in v
    G.col(i) =
        constraintValues(response(Vec4(v_d + Vec4::Unit(i))), limit, k, double_support) - c0;
  const Eigen::VectorXd h = G * v_d - c0;
  SmallQpResult qp = solveLeastDistanceQp(G, h, w, v_d);
  Projected p{qp.x, true, !qp.feasible};
  if (!qp.feasible) p.v = solveLeastDistanceQp(G.topRows(8), h.head(8), w, v_d).x;
  return p;
}

ContactLimits contactLimits(const ClosedLoop& s) {
  return {s.options.friction_coefficient, s.options.min_normal_force, s.options.ground_slope};
}

Vec4 torqueLimits(const ClosedLoop& s, const Vec5& qd) {
  return jointTorqueLimits(s.controller.robot.envelope, jointSpeeds(qd),
                           s.options.full_torque_envelope);
}

// α past α_fSS over which a held reference's slope decays [rad] (≈ 20 ms at the default
// gait's α̇): a C¹ hold, where a step of the slope would make the PD demand a torque spike that
// slips the stance foot.
constexpr double kHoldLength = 0.02;

// δ_d,j(α) and its α-derivatives. Past α_fSS with hold_references_past_fss the reference is held
// C¹: δ_d(α_f) + δ_d'(α_f) σ τ (1 − e^{−d/τ}), d = σ (α − α_f) ≥ 0 the distance past α_fSS
// along the step's direction σ, τ = kHoldLength.
PolyValue<double> ssReference(const ClosedLoop& s, int j, double alpha) {
  const GaitMotion<double>& mo = s.motion;
  const double sigma = mo.alpha_fSS > mo.q_iSS(0) ? 1.0 : -1.0;
  const double d = sigma * (alpha - mo.alpha_fSS);
  if (!s.options.hold_references_past_fss || d <= 0.0) return mo.ss_path[j](alpha);
  const PolyValue<double> f = mo.ss_path[j](mo.alpha_fSS);
  const double decay = std::exp(-d / kHoldLength);
  return {f.value + f.first * sigma * kHoldLength * (1.0 - decay), f.first * decay,
          -f.first * decay * sigma / kHoldLength};
}

// SS input–output linearisation: Γ with B A⁻¹ D_Γ Γ = ÿ* + δ_d'' α̇² + B A⁻¹ (C + G), where
// y = δ − δ_d(α), ẏ = B q̇, B = [−δ_d'(α) | I], ÿ* = −ω² y − 2ω ẏ. With touchdown by foot
// height, α may pass α_fSS before the foot lands: the polynomials δ_d are then extrapolated
// for an impact landing (the thesis freezes them at α_fSS, §4.3.1.3, which steps the
// reference's slope and makes the PD demand a torque spike) and held for a zero-velocity
// landing (ClosedLoopOptions::hold_references_past_fss: only the freeze brings its foot down).
Vec4 ssControl(const ClosedLoop& s, const Vec5& q, const Vec5& qd, ClosedLoopPoint& e) {
  const Model& c = s.controller;
  const PinnedTerms<double> t = pinnedTerms(c, q, qd);
  Eigen::Matrix<double, 4, 5> B = Eigen::Matrix<double, 4, 5>::Zero();
  Vec4 curvature;
  for (int j = 0; j < 4; ++j) {
    const PolyValue<double> v = ssReference(s, j, q(0));
    B(j, 0) = -v.first;
    B(j, j + 1) = 1.0;
    e.error(j) = q(j + 1) - v.value;
    curvature(j) = v.second * qd(0) * qd(0);
  }
  const Eigen::LDLT<Mat5> A(t.A);
  const Eigen::Matrix4d Lg = B * A.solve(c.D_Gamma);
  const Vec4 drift = curvature + B * A.solve(Vec5(t.C + t.G));
  const Eigen::PartialPivLU<Eigen::Matrix4d> lu(Lg);
  const Vec4 friction = frictionTorque(c, jointSpeeds(qd), SignMode::Smooth);
  const auto response = [&](const Vec4& v) {
    InputResponse r;
    r.gamma_star = lu.solve(Vec4(v + drift)) + friction;
    const Vec5 qdd = A.solve(Vec5(c.D_Gamma * (r.gamma_star - friction) - t.C - t.G));  // (1.32)
    const Vec2 acc = pinnedComAcceleration(c, q, qd, qdd);
    r.R1 = Vec2(c.total_mass * acc(0), c.total_mass * (acc(1) + c.gravity));
    r.R2.setZero();
    return r;
  };
  const double w = s.options.bandwidth;
  const Vec4 v_d = -w * w * e.error - 2.0 * w * (B * qd);
  if (!s.options.torque_limits) return response(v_d).gamma_star;
  const Projected p = projectInputs(response, v_d, Vec4::Ones(), torqueLimits(s, qd),
                                    contactLimits(s), false);
  e.saturated = p.saturated;
  e.projection_infeasible = p.infeasible;
  return response(p.v).gamma_star;
}

// Weight of the δ1, δ2 output accelerations against α̈ in the time-optimal projection: the
// constraints are met by giving up α̈ first, as in the 2-variable LPs (4.14).
constexpr double kOutputWeight = 1e4;

// DS inputs v = (α̈, ÿ1, ÿ2, R2x) → (α̈, δ̈1, δ̈2) = T v.head(3) + b, with their desired values.
struct DsInputs {
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  Eigen::Vector3d b = Eigen::Vector3d::Zero(), v_d;
  Vec4 weights;
};

// Cubic control: (α, δ1, δ2) track α_r(t) and δ_d(α_r(t)) (PD, v the accelerations).
DsInputs cubicDsInputs(const ClosedLoop& s, const DsReference& ds, double t, const Vec5& q,
                       const Vec5& qd, Vec4& error) {
  const GaitMotion<double>& mo = s.motion;
  const PolyValue<double> a = ds.alpha(t);
  const PolyValue<double> d1 = mo.ds_delta1(a.value), d2 = mo.ds_delta2(a.value);
  const Eigen::Vector3d p(a.value, d1.value, d2.value);
  const Eigen::Vector3d pd(a.first, d1.first * a.first, d2.first * a.first);
  const Eigen::Vector3d pdd(a.second, d1.second * a.first * a.first + d1.first * a.second,
                            d2.second * a.first * a.first + d2.first * a.second);
  const Eigen::Vector3d err = p - q.head<3>(), errd = pd - qd.head<3>();
  error << err, 0.0;
  const double w = s.options.bandwidth;
  DsInputs in;
  in.v_d = pdd + w * w * err + 2.0 * w * errd;
  in.weights << 1.0, 1.0, 1.0, kR2xWeight;
  return in;
}

// Time-optimal control (4.1): α̈ → the cyclic curve α̇_c(α) (P only, (4.58)), outputs
// y = δ − δ_d(α) of the measured α driven to 0 (PD, v = ÿ).
DsInputs timeOptimalDsInputs(const ClosedLoop& s, const Vec5& q, const Vec5& qd, Vec4& error) {
  const GaitMotion<double>& mo = s.motion;
  const CyclicDsPoint c = cyclicDsAlpha(mo, q(0));
  const PolyValue<double> d1 = mo.ds_delta1(q(0)), d2 = mo.ds_delta2(q(0));
  const Eigen::Vector2d y(q(1) - d1.value, q(2) - d2.value);
  const Eigen::Vector2d yd(qd(1) - d1.first * qd(0), qd(2) - d2.first * qd(0));
  error << c.alphad - qd(0), y, 0.0;
  const double w = s.options.bandwidth;
  // The bounds at (α, α̇) with the contact rows of the projection (4.60), its R_min included.
  const DsAccelerationBounds b = dsAccelerationBounds(
      s.controller, mo,
      {s.options.friction_coefficient, s.options.min_normal_force, s.options.full_torque_envelope},
      q(0), qd(0));
  double alphadd = c.slope * qd(0) + kTimeOptimalGain * (c.alphad - qd(0));  // α̈_c on the curve
  if (b.defined) alphadd = std::clamp(alphadd, b.min, b.max);                // (4.1)
  DsInputs in;
  in.v_d << alphadd, Eigen::Vector2d(-w * w * y - 2.0 * w * yd);
  in.T.block<2, 1>(1, 0) << d1.first, d2.first;
  in.b << 0.0, d1.second * qd(0) * qd(0), d2.second * qd(0) * qd(0);
  in.weights << 1.0, kOutputWeight, kOutputWeight, kR2xWeight;
  return in;
}

// DS: δ3, δ4 accelerations from the closed chain (1.35); R2x, the fourth input, of least
// Γ*ᵀΓ* within both friction cones (the 1-D QP (3.68)–(3.70) of the gait's force split), then
// the projection (4.60).
Vec4 dsControl(const ClosedLoop& s, const DsReference& ds, double t, const Vec5& q, const Vec5& qd,
               ClosedLoopPoint& e) {
  const Model& c = s.controller;
  const bool optimal = s.options.ds_control == DsAlphaControl::TimeOptimal;
  const DsInputs in =
      optimal ? timeOptimalDsInputs(s, q, qd, e.error) : cubicDsInputs(s, ds, t, q, qd, e.error);
  const ChainState<double> st = chainState(c, q, qd);
  const Matrix25<double> D2 = chainPointJacobian(c, c.pinned.foot2, st);
  const Vec2 H2 = chainPointBias(c.pinned.foot2, st);
  const Eigen::Matrix2d D245_inv = D2.rightCols<2>().inverse();
  const double M = c.total_mass;
  const auto affine = [&](const Eigen::Vector3d& v) {
    const Eigen::Vector3d acc = in.T * v + in.b;
    Vec5 qdd;
    qdd << acc, -D245_inv * (D2.leftCols<3>() * acc + H2);
    return doubleSupportAffine(c, q, qd, qdd, SignMode::Smooth);
  };
  const auto response = [&](const Vec4& v) {
    const DoubleSupportAffine<double> aff = affine(v.head<3>());
    InputResponse r;
    r.gamma_star = aff.J - aff.K * v(3);
    r.R2 = Vec2(v(3), aff.R2z0 + aff.R2z_slope * v(3));
    r.R1 = M * Vec2(aff.com_acceleration(0), aff.com_acceleration(1) + c.gravity) - r.R2;
    return r;
  };
  const DoubleSupportAffine<double> aff = affine(in.v_d);
  const double mu = s.options.friction_coefficient;
  const double R1z0 = M * (aff.com_acceleration(1) + c.gravity) - aff.R2z0;  // (3.59)
  const DsBounds<double> bounds =
      r2xBounds(R1z0, aff.R2z0, M * aff.com_acceleration(0), mu, kBranchFree);  // (3.66)
  Vec4 v_d;
  v_d << in.v_d, r2xMinTorque(aff.J, aff.K, bounds, kBranchFree).r2x;  // (3.68)–(3.70)
  if (!s.options.torque_limits) return response(v_d).gamma_star;
  const Projected pr =
      projectInputs(response, v_d, in.weights, torqueLimits(s, qd), contactLimits(s), true);
  e.saturated = pr.saturated;
  e.projection_infeasible = pr.infeasible;
  return response(pr.v).gamma_star;
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

}  // namespace

const char* outcomeName(WalkOutcome o) {
  switch (o) {
    case WalkOutcome::Completed:
      return "completed";
    case WalkOutcome::ImpactUnavailable:
      return "impact_model_unavailable";
    case WalkOutcome::EarlyTouchdown:
      return "early_touchdown";
    case WalkOutcome::StanceLiftOff:
      return "stance_lift_off";
    case WalkOutcome::Fell:
      return "fell";
    case WalkOutcome::Slipped:
      return "slipped";
    case WalkOutcome::RearFootLift:
      return "rear_foot_lift";
  }
  return "unknown";
}

const char* toString(DsAlphaControl c) {
  return c == DsAlphaControl::Cubic ? "cubic" : "time_optimal";
}

DsReference dsReference(const ClosedLoop& s, double t, const Vec5& q, const Vec5& qd) {
  const GaitMotion<double>& mo = s.motion;
  DsReference r;
  r.t_start = t;
  // Time-optimal control ends at α_fDS; t_end is then the time allowed before it counts as a
  // fall (ten planned DS durations).
  r.t_end = t + (s.options.ds_control == DsAlphaControl::TimeOptimal ? 10.0 : 1.0) * mo.T_DS;
  // DS control of α: from the touchdown state to the cycle's (α_fDS, α̇_iSS) at lift-off.
  r.alpha = cubicHermite(t, q(0), qd(0), r.t_end, mo.ds_alpha(mo.T_DS).value, mo.alphadot_iSS);
  return r;
}

ClosedLoopPoint evaluateClosedLoop(const ClosedLoop& s, bool ss, const DsReference& ds, double t,
                                   const Vec5& q, const Vec5& qd) {
  const Model& p = s.plant;
  ClosedLoopPoint e;
  e.gamma_star = ss ? ssControl(s, q, qd, e) : dsControl(s, ds, t, q, qd, e);
  e.friction = frictionTorque(p, jointSpeeds(qd), SignMode::Smooth);
  if (ss) {
    e.qdd = forwardDynamicsSS(p, q, qd, e.gamma_star, SignMode::Smooth);
    e.R2.setZero();
  } else {
    dsPlant(p, q, qd, e.gamma_star - e.friction, e.qdd, e.R2);
  }
  const Vec2 acc = pinnedComAcceleration(p, q, qd, e.qdd);
  e.R1 = toGroundFrame(s, Vec2(p.total_mass * acc(0), p.total_mass * (acc(1) + p.gravity)) - e.R2);
  e.R2 = toGroundFrame(s, e.R2);
  return e;
}

void closedLoopRhs(const ClosedLoop& s, bool ss, const DsReference& ds, double t,
                   const Eigen::VectorXd& y, Eigen::VectorXd& f) {
  const Vec5 qd = y.segment<5>(5);
  const ClosedLoopPoint e = evaluateClosedLoop(s, ss, ds, t, y.head<5>(), qd);
  const Vec4 w = jointSpeeds(qd);
  f.resize(kClosedLoopStateSize);
  f << qd, e.qdd, w.dot(e.gamma_star), w.dot(e.friction);
}

Vec2 toGroundFrame(const ClosedLoop& s, const Vec2& v) {
  return Eigen::Rotation2Dd(-s.options.ground_slope) * v;
}

bool touchdownArmed(const ClosedLoop& s, const Vec5& q) {
  const GaitMotion<double>& mo = s.motion;
  return (q(0) - 0.5 * (mo.q_iSS(0) + mo.alpha_fSS)) * (mo.alpha_fSS - mo.q_iSS(0)) > 0.0;
}

double touchdownEvent(const ClosedLoop& s, const Vec5& q) {
  if (!s.options.touchdown_by_foot_height) return q(0) - s.motion.alpha_fSS;
  if (!touchdownArmed(s, q)) return 1.0;
  const Vec2 foot2 = chainPoint(s.plant.pinned.foot2, chainState(s.plant, q, Vec5(Vec5::Zero())));
  return toGroundFrame(s, foot2)(1);
}

double touchdownEventRate(const ClosedLoop& s, const Vec5& q, const Vec5& qd) {
  if (!s.options.touchdown_by_foot_height) return qd(0);
  return toGroundFrame(s, Vec2(pinnedTerms(s.plant, q, qd).D2 * qd))(1);
}

void closedLoopEvents(const ClosedLoop& s, bool ss, const DsReference& ds, double t,
                      const Eigen::VectorXd& y, Eigen::VectorXd& g) {
  const Vec5 q = y.head<5>(), qd = y.segment<5>(5);
  const ClosedLoopPoint e = evaluateClosedLoop(s, ss, ds, t, q, qd);
  const Model& p = s.plant;
  const double mu = s.options.plant_friction_coefficient;
  const double slack = kContactTolerance * p.total_mass * p.gravity;
  // Slip: a cone row of the plant's μ above the slack (the rows negated: g > 0 while it holds).
  const std::array<double, 2> cone1 = frictionConeRows(e.R1, mu);
  const std::array<double, 2> cone2 = frictionConeRows(e.R2, mu);
  g.resize(kClosedLoopEvents);
  if (ss) {
    const ChainState<double> st = chainState(p, q, qd);
    const double foot2_z = toGroundFrame(s, chainPoint(p.pinned.foot2, st))(1);
    const bool by_height = s.options.touchdown_by_foot_height;
    const bool armed = by_height && touchdownArmed(s, q);
    g << touchdownEvent(s, q), armed ? 1.0 : foot2_z + kGroundTolerance, e.R1(1) + slack,
        toGroundFrame(s, chainPoint(p.pinned.hip, st))(1) - kFallHipHeight, -qd(0), -cone1[1] + slack,
        -cone1[0] + slack;
  } else {
    // DS end: T_DS elapsed (cubic control), or α reaches α_fDS (time-optimal control, §4.3.1).
    const bool optimal = s.options.ds_control == DsAlphaControl::TimeOptimal;
    g << (optimal ? q(0) - s.motion.ds_alpha(s.motion.T_DS).value : ds.t_end - t), e.R1(1) + slack,
        e.R2(1) + slack, -cone1[1] + slack, -cone1[0] + slack, -cone2[1] + slack,
        -cone2[0] + slack;
  }
}

TouchdownMap impulseFreeTouchdown(double speed_tol, bool double_support) {
  return [speed_tol, double_support](const Model& plant, const Vec5& q, const Vec5& qd) {
    TouchdownResult r;
    const double speed = (pinnedTerms(plant, q, qd).D2 * qd).norm();
    if (speed > speed_tol) {
      r.why = "touchdown with non-zero velocity " + std::to_string(speed) +
              " m/s: impact model not available";
      return r;
    }
    r.ok = true;
    r.q_plus = exchangeLegs(q);             // (3.22)
    r.qd_plus = exchangeLegVelocities(qd);  // (3.23)
    r.double_support_follows = double_support;
    return r;
  };
}

TouchdownResult touchdownOnGround(const ClosedLoop& s, const TouchdownMap& map, const Vec5& q,
                                  const Vec5& qd) {
  // Adding φ to α turns the whole robot by φ about foot 1 (every θ_k contains α, (1.13)).
  const Vec5 turn = s.options.ground_slope * Vec5::Unit(0);
  TouchdownResult r = map(s.plant, q - turn, qd);
  if (r.ok) r.q_plus += turn;  // the relabelled α is again an absolute angle
  return r;
}

}  // namespace gaitopt
