#include "gaitopt/control/walking_controller.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>

#include "gaitopt/control/control_constraints.hpp"
#include "gaitopt/control/ds_acceleration_bounds.hpp"
#include "gaitopt/gait/constraints/torque_envelope.hpp"
#include "gaitopt/gait/ds_force_distribution.hpp"
#include "gaitopt/math/small_qp.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/forward_dynamics.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"

namespace gaitopt {
namespace {

// Weight of R2x [1/N²] against the DS output accelerations [1/(rad/s²)²] in (4.60): the thesis
// leaves R2x out of the objective (non-unique); a small weight keeps the least-torque choice
// unless the constraints need another.
constexpr double kR2xWeight = 1e-6;
// [N·m, N] a constraint row within this of its bound holds: optimised gaits ride on their
// torque limits and friction cones, which round-off must not count as a violation.
constexpr double kConstraintTolerance = 1e-8;

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

ContactLimits contactLimits(const WalkingController& s) {
  return {s.options.friction_coefficient, s.options.min_normal_force, s.options.ground_slope};
}

Vec4 torqueLimits(const WalkingController& s, const Vec5& qd) {
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
PolyValue<double> plannedSsReference(const WalkingController& s, int j, double alpha) {
  const GaitMotion<double>& mo = s.motion;
  const double sigma = mo.alpha_fSS > mo.q_iSS(0) ? 1.0 : -1.0;
  const double d = sigma * (alpha - mo.alpha_fSS);
  if (!s.options.hold_references_past_fss || d <= 0.0) return mo.ss_path[j](alpha);
  const PolyValue<double> f = mo.ss_path[j](mo.alpha_fSS);
  const double decay = std::exp(-d / kHoldLength);
  return {f.value + f.first * sigma * kHoldLength * (1.0 - decay), f.first * decay,
          -f.first * decay * sigma / kHoldLength};
}

// Four outputs y of the pinned model, affine in the accelerations: ẏ = B q̇ − ȯ, ÿ = B q̈ − c
// (c the part quadratic in q̇), with the offsets o(t) of the options on their rows.
struct PinnedOutputs {
  Eigen::Matrix<double, 4, 5> B = Eigen::Matrix<double, 4, 5>::Zero();
  Vec4 c = Vec4::Zero();
};

// Input–output linearisation of four outputs on the pinned model (one foot on the ground):
// Γ with B A⁻¹ D_Γ Γ = ÿ* + c + B A⁻¹ (C + G), ÿ* = −ω² y − 2ω ẏ (+ the offsets' ȯ, ö), then
// the projection (4.57).
Vec4 outputControl(const WalkingController& s, const Vec5& q, const Vec5& qd,
                   const PinnedOutputs& y, ControlOutput& e) {
  const Model& c = s.controller;
  const PinnedTerms<double> t = pinnedTerms(c, q, qd);
  const Eigen::LDLT<Mat5> A(t.A);
  const Eigen::Matrix4d Lg = y.B * A.solve(c.D_Gamma);
  const Vec4 drift = y.c + y.B * A.solve(Vec5(t.C + t.G));
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
  const PdGains k = pdGains(s.options);
  const TimedOffset& o = s.options.timed_offset;
  const Vec4 v_d = -k.kp * e.error - k.kd * (y.B * qd) + (k.kd * o.rate + o.acceleration);
  if (!s.options.torque_limits) return response(v_d).gamma_star;
  const Projected p = projectInputs(response, v_d, Vec4::Ones(), torqueLimits(s, qd),
                                    contactLimits(s), false);
  e.saturated = p.saturated;
  e.projection_infeasible = p.infeasible;
  return response(p.v).gamma_star;
}

// SS: the virtual constraints y = δ − δ_d(α), B = [−δ_d'(α) | I], c = δ_d'' α̇². With touchdown
// by foot height, α may pass α_fSS before the foot lands: the polynomials δ_d are then
// extrapolated for an impact landing (the thesis freezes them at α_fSS, §4.3.1.3, which steps
// the reference's slope and makes the PD demand a torque spike) and held for a zero-velocity
// landing (ControllerOptions::hold_references_past_fss: only the freeze brings its foot down).
Vec4 ssControl(const WalkingController& s, const Vec5& q, const Vec5& qd, ControlOutput& e) {
  PinnedOutputs y;
  // The weight of ControllerOptions::swing_end_offset: the smoothstep of the SS phase s(α).
  const GaitMotion<double>& mo = s.motion;
  const PolyValue<double> blend = smoothstep(q(0), mo.q_iSS(0), mo.alpha_fSS - mo.q_iSS(0));
  for (int j = 0; j < 4; ++j) {
    PolyValue<double> v = plannedSsReference(s, j, q(0));
    const double end = s.options.swing_end_offset(j);
    v = {v.value + end * blend.value, v.first + end * blend.first, v.second + end * blend.second};
    y.B(j, 0) = -v.first;
    y.B(j, j + 1) = 1.0;
    e.error(j) = q(j + 1) - v.value - s.options.timed_offset.value(j);
    y.c(j) = v.second * qd(0) * qd(0);
  }
  return outputControl(s, q, qd, y, e);
}

// Re-contact: the DS references of δ1, δ2 at the measured α (with their offsets) and the foot-2
// point driven to `target` in the pinned frame (rows ÿ = D2 q̈ + H2: c = −H2).
Vec4 recontactControl(const WalkingController& s, const Vec2& target, const Vec5& q,
                      const Vec5& qd, ControlOutput& e) {
  const GaitMotion<double>& mo = s.motion;
  const Model& m = s.controller;
  const ChainState<double> st = chainState(m, q, qd);
  const TimedOffset& o = s.options.timed_offset;
  PinnedOutputs y;
  const PolyValue<double> d[2] = {mo.ds_delta1(q(0)), mo.ds_delta2(q(0))};
  for (int j = 0; j < 2; ++j) {
    y.B(j, 0) = -d[j].first;
    y.B(j, j + 1) = 1.0;
    e.error(j) = q(j + 1) - d[j].value - o.value(j);
    y.c(j) = d[j].second * qd(0) * qd(0);
  }
  y.B.bottomRows<2>() = chainPointJacobian(m, m.pinned.foot2, st);
  y.c.tail<2>() = -chainPointBias(m.pinned.foot2, st);
  e.error.tail<2>() = chainPoint(m.pinned.foot2, st) - target;
  ControllerOptions options = s.options;
  options.timed_offset.value.tail<2>().setZero();
  options.timed_offset.rate.tail<2>().setZero();
  options.timed_offset.acceleration.tail<2>().setZero();
  return outputControl({mo, m, options}, q, qd, y, e);
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
DsInputs cubicDsInputs(const WalkingController& s, const DsReference& ds, double t, const Vec5& q,
                       const Vec5& qd, Vec4& error) {
  const GaitMotion<double>& mo = s.motion;
  const PolyValue<double> a = ds.alpha(t);
  const PolyValue<double> d1 = mo.ds_delta1(a.value), d2 = mo.ds_delta2(a.value);
  const TimedOffset& o = s.options.timed_offset;
  const Eigen::Vector3d p(a.value, d1.value + o.value(0), d2.value + o.value(1));
  const Eigen::Vector3d pd(a.first, d1.first * a.first + o.rate(0), d2.first * a.first + o.rate(1));
  const Eigen::Vector3d pdd(
      a.second, d1.second * a.first * a.first + d1.first * a.second + o.acceleration(0),
      d2.second * a.first * a.first + d2.first * a.second + o.acceleration(1));
  const Eigen::Vector3d err = p - q.head<3>(), errd = pd - qd.head<3>();
  error << err, 0.0;
  const PdGains k = pdGains(s.options);
  DsInputs in;
  in.v_d = pdd + k.kp * err + k.kd * errd;
  in.weights << 1.0, 1.0, 1.0, kR2xWeight;
  return in;
}

// Time-optimal control (4.1): α̈ → the cyclic curve α̇_c(α) (P only, (4.58)), outputs
// y = δ − δ_d(α) of the measured α driven to 0 (PD, v = ÿ).
DsInputs timeOptimalDsInputs(const WalkingController& s, const DsReference& ds, const Vec5& q,
                             const Vec5& qd, Vec4& error) {
  const GaitMotion<double>& mo = s.motion;
  CyclicDsPoint c = cyclicDsAlpha(mo, q(0));
  c.alphad *= ds.rate_scale;  // the curve scaled: α̈_c = slope α̇ still holds on it
  const PolyValue<double> d1 = mo.ds_delta1(q(0)), d2 = mo.ds_delta2(q(0));
  const TimedOffset& o = s.options.timed_offset;
  const Eigen::Vector2d y(q(1) - d1.value - o.value(0), q(2) - d2.value - o.value(1));
  const Eigen::Vector2d yd(qd(1) - d1.first * qd(0) - o.rate(0), qd(2) - d2.first * qd(0) - o.rate(1));
  error << c.alphad - qd(0), y, 0.0;
  const PdGains k = pdGains(s.options);
  // The bounds at (α, α̇) with the contact rows of the projection (4.60), its R_min included.
  const DsAccelerationBounds b = dsAccelerationBounds(
      s.controller, mo,
      {s.options.friction_coefficient, s.options.min_normal_force, s.options.full_torque_envelope},
      q(0), qd(0));
  double alphadd = c.slope * qd(0) + kTimeOptimalGain * (c.alphad - qd(0));  // α̈_c on the curve
  if (b.defined) alphadd = std::clamp(alphadd, b.min, b.max);                // (4.1)
  DsInputs in;
  in.v_d << alphadd, Eigen::Vector2d(-k.kp * y - k.kd * yd + o.acceleration.head<2>());
  in.T.block<2, 1>(1, 0) << d1.first, d2.first;
  in.b << 0.0, d1.second * qd(0) * qd(0), d2.second * qd(0) * qd(0);
  in.weights << 1.0, kOutputWeight, kOutputWeight, kR2xWeight;
  return in;
}

// DS: δ3, δ4 accelerations from the closed chain (1.35); R2x, the fourth input, of least
// Γ*ᵀΓ* within both friction cones (the 1-D QP (3.68)–(3.70) of the gait's force split), then
// the projection (4.60).
Vec4 dsControl(const WalkingController& s, const DsReference& ds, double t, const Vec5& q, const Vec5& qd,
               ControlOutput& e) {
  const Model& c = s.controller;
  const bool optimal = s.options.ds_control == DsAlphaControl::TimeOptimal;
  const DsInputs in =
      optimal ? timeOptimalDsInputs(s, ds, q, qd, e.error) : cubicDsInputs(s, ds, t, q, qd, e.error);
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
}  // namespace

PdGains pdGains(const ControllerOptions& o) {
  return {o.gain_scale * o.bandwidth * o.bandwidth, o.gain_scale * 2.0 * o.bandwidth};
}

const char* toString(DsAlphaControl c) {
  return c == DsAlphaControl::Cubic ? "cubic" : "time_optimal";
}

DsReference dsReference(const WalkingController& s, double t, const Vec5& q, const Vec5& qd,
                        double rate_scale) {
  const GaitMotion<double>& mo = s.motion;
  DsReference r;
  r.t_start = t;
  r.rate_scale = rate_scale;
  // Time-optimal control ends at α_fDS; t_end is then the time allowed before it counts as a
  // fall (ten planned DS durations).
  r.t_end = t + (s.options.ds_control == DsAlphaControl::TimeOptimal ? 10.0 : 1.0) * mo.T_DS;
  // DS control of α: from the touchdown state to the cycle's (α_fDS, α̇_iSS) at lift-off.
  r.alpha = cubicHermite(t, q(0), qd(0), r.t_end, mo.ds_alpha(mo.T_DS).value,
                         rate_scale * mo.alphadot_iSS);
  return r;
}

ControlOutput singleSupportControl(const WalkingController& s, const Vec5& q, const Vec5& qd) {
  ControlOutput e;
  e.gamma_star = ssControl(s, q, qd, e);
  return e;
}

ControlOutput recontactControl(const WalkingController& s, const Vec2& target, const Vec5& q,
                               const Vec5& qd) {
  ControlOutput e;
  e.gamma_star = recontactControl(s, target, q, qd, e);
  return e;
}

ControlOutput doubleSupportControl(const WalkingController& s, const DsReference& ds, double t,
                                   const Vec5& q, const Vec5& qd) {
  ControlOutput e;
  e.gamma_star = dsControl(s, ds, t, q, qd, e);
  return e;
}

}  // namespace gaitopt
