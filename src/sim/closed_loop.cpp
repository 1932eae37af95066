#include "gaitopt/sim/closed_loop.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

#include "gaitopt/gait/constraints/contact.hpp"
#include "gaitopt/gait/leg_geometry.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/forward_dynamics.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"

namespace gaitopt {
namespace {

constexpr double kGroundTolerance = 1e-6;  // [m] swing foot below the ground: early touchdown
constexpr double kFallHipHeight = 0.3;     // [m]
// Fraction of the plant's weight by which a contact constraint of the plant may be violated
// before it counts (|Rx| > μ Rz: slip; Rz < 0: lift-off): the optimised DS puts R2x on the
// cone of the gait's μ, and the projection (4.60) holds a normal force at 0 (round-off margin).
constexpr double kContactTolerance = 1e-7;


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
    case WalkOutcome::IntegrationFailed:
      return "integration_failed";
  }
  return "unknown";
}


WalkingController controllerOf(const ClosedLoop& s) {
  return {s.motion, s.controller, s.options};
}

DsReference dsReference(const ClosedLoop& s, double t, const Vec5& q, const Vec5& qd) {
  return dsReference(controllerOf(s), t, q, qd);
}

ClosedLoopPoint evaluateClosedLoop(const ClosedLoop& s, bool ss, const DsReference& ds, double t,
                                   const Vec5& q, const Vec5& qd) {
  const Model& p = s.plant;
  const WalkingController law = controllerOf(s);
  const ControlOutput c =
      ss ? singleSupportControl(law, q, qd) : doubleSupportControl(law, ds, t, q, qd);
  ClosedLoopPoint e;
  e.gamma_star = c.gamma_star;
  e.error = c.error;
  e.saturated = c.saturated;
  e.projection_infeasible = c.projection_infeasible;
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
  const std::array<double, 2> no_slip{-1.0, -1.0};
  const std::array<double, 2> cone1 = s.options.detect_slip ? frictionConeRows(e.R1, mu) : no_slip;
  const std::array<double, 2> cone2 = s.options.detect_slip ? frictionConeRows(e.R2, mu) : no_slip;
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
