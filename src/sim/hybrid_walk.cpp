#include "gaitopt/sim/hybrid_walk.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/forward_dynamics.hpp"

namespace gaitopt {
ClosedLoopOptions closedLoopOptions(const WalkRequest& r) {
  ClosedLoopOptions o;
  o.bandwidth = r.bandwidth;
  o.gain_scale = r.gain_scale;
  o.friction_coefficient = r.friction_coefficient;
  o.plant_friction_coefficient =
      r.plant_friction_coefficient < 0.0 ? r.friction_coefficient : r.plant_friction_coefficient;
  o.detect_slip = r.detect_slip;
  o.min_normal_force = r.min_normal_force;
  o.ground_slope = r.ground_slope;
  o.torque_limits = r.torque_limits;
  o.full_torque_envelope = r.full_torque_envelope;
  o.touchdown_by_foot_height = r.touchdown_by_foot_height;
  o.hold_references_past_fss = r.hold_references_past_fss;
  o.ds_control = r.ds_control;
  return o;
}

namespace {

class Walker {
 public:
  Walker(const GaitEvaluation<double>& e, const Model& c, const Model& p, const WalkRequest& r,
         const TouchdownMap& td)
      : sys_{e.motion, c, p, closedLoopOptions(r)},
        mo_(e.motion),
        req_(r),
        td_(td),
        cv_(
            kClosedLoopStateSize,
            [this](double t, const Eigen::VectorXd& y, Eigen::VectorXd& f) {
              closedLoopRhs(sys_, ss_, ds_, t, y, f);
            },
            kClosedLoopEvents,
            [this](double t, const Eigen::VectorXd& y, Eigen::VectorXd& g) {
              closedLoopEvents(sys_, ss_, ds_, t, y, g);
            },
            r.tolerances) {}

  WalkResult run();

 private:
  const ClosedLoop sys_;
  const GaitMotion<double>& mo_;
  const WalkRequest& req_;
  const TouchdownMap& td_;
  CvodeIntegrator cv_;
  bool ss_ = true;
  DsReference ds_;
  WalkResult out_;

  void record(double t, const Eigen::VectorXd& y, int step) {
    const ClosedLoopPoint e = evaluateClosedLoop(sys_, ss_, ds_, t, y.head<5>(), y.segment<5>(5));
    out_.samples.push_back({t, step, ss_, y.head<5>(), y.segment<5>(5), e.qdd, e.gamma_star,
                            e.error, e.R1, e.R2, e.saturated});
    WalkStep& s = out_.steps.back();
    if (ss_) s.max_output_error = std::max(s.max_output_error, e.error.cwiseAbs().maxCoeff());
    s.min_normal_force = std::min({s.min_normal_force, e.R1(1), ss_ ? e.R1(1) : e.R2(1)});
    if (e.saturated && s.saturated_samples++ == 0) s.first_saturation_time = t;
  }

  // Integrates the current phase to its end event, recording samples; returns the event.
  CvodeIntegrator::Result phase(double t0, const Eigen::VectorXd& y0, int step) {
    cv_.reset(t0, y0);
    record(t0, y0, step);
    // Events are falling crossings; a force or fall condition already violated at the phase
    // start is one too (the swing foot starts on the ground after touchdown: not checked).
    Eigen::VectorXd g;
    closedLoopEvents(sys_, ss_, ds_, t0, y0, g);
    for (int i = 0; i < kClosedLoopEvents; ++i)
      if (g(i) < 0.0 && !(ss_ && (i == kTouchdown || i == kSwingBelowGround))) return {t0, y0, i};
    const double dt = 1.0 / req_.sample_rate;
    double next = (std::floor(t0 / dt) + 1.0) * dt;
    for (;;) {
      CvodeIntegrator::Result r = cv_.advance(ss_ ? next : std::min(next, ds_.t_end));
      record(r.t, r.y, step);
      if (r.root >= 0 || (!ss_ && r.t >= ds_.t_end)) return r;
      next += dt;
    }
  }

  bool fail(WalkOutcome o, const std::string& msg) {
    out_.outcome = o;
    out_.message = msg;
    return false;
  }

  std::string at(int k, double t) const {
    return "step " + std::to_string(k) + " at t = " + std::to_string(t) + " s";
  }

  void startStep(double t, Eigen::VectorXd& y, int k);
  void endStep(const Eigen::VectorXd& y);
  bool singleSupport(double& t, Eigen::VectorXd& y, int k);
  bool touchdown(double t, Eigen::VectorXd& y, int k);
  bool doubleSupport(double& t, Eigen::VectorXd& y, int k);
  bool walkStep(double& t, Eigen::VectorXd& y, int k);
};

void Walker::startStep(double t, Eigen::VectorXd& y, int k) {
  WalkStep s;
  s.step = k;
  s.t_start = t;
  s.alphad_start = y(5);
  s.energy_start = pinnedEnergy(sys_.plant, y.head<5>(), y.segment<5>(5));
  s.min_normal_force = std::numeric_limits<double>::infinity();
  out_.steps.push_back(s);
  y(10) = y(11) = 0.0;
}

// The step ends at the next SS start (after lift-off, or at once after an impact that lifts
// foot 1): its energy there, in the new stance labelling with the potential still measured
// from the step's stance foot (the new one is higher by touchdown_rise on a slope), and the
// step's work integrals.
void Walker::endStep(const Eigen::VectorXd& y) {
  WalkStep& s = out_.steps.back();
  const Model& p = sys_.plant;
  s.energy_end = pinnedEnergy(p, y.head<5>(), y.segment<5>(5)) +
                 p.total_mass * p.gravity * s.touchdown_rise;
  s.step_motor_work = y(10);
  s.step_friction_loss = y(11);
}

bool Walker::singleSupport(double& t, Eigen::VectorXd& y, int k) {
  ss_ = true;
  const CvodeIntegrator::Result r = phase(t, y, k);
  t = r.t;
  y = r.y;
  switch (r.root) {
    case kSwingBelowGround:
      return fail(WalkOutcome::EarlyTouchdown, "swing foot below the ground, " + at(k, t));
    case kStanceNormal:
      return fail(WalkOutcome::StanceLiftOff, "stance foot normal force < 0, " + at(k, t));
    case kHipLow:
    case kAlphaStalls:
      return fail(WalkOutcome::Fell, "fell back or down, " + at(k, t));
    case kStanceSlipForward:
    case kStanceSlipBackward:
      return fail(WalkOutcome::Slipped, "stance foot left its friction cone, " + at(k, t));
    default:
      break;
  }
  const Vec5 q = y.head<5>(), qd = y.segment<5>(5);
  WalkStep& st = out_.steps.back();
  st.t_touchdown = t;
  st.touchdown_event_residual =
      std::abs(touchdownEvent(sys_, q)) / std::abs(touchdownEventRate(sys_, q, qd));
  st.touchdown_foot_speed = (pinnedTerms(sys_.plant, q, qd).D2 * qd).norm();
  st.touchdown_rise = chainPoint(sys_.plant.pinned.foot2, chainState(sys_.plant, q, qd))(1);
  st.energy_touchdown = pinnedEnergy(sys_.plant, q, qd);
  st.motor_work = y(10);
  st.friction_loss = y(11);
  return touchdown(t, y, k);
}

bool Walker::touchdown(double t, Eigen::VectorXd& y, int k) {
  const TouchdownResult td = touchdownOnGround(sys_, td_, y.head<5>(), y.segment<5>(5));
  if (!td.ok) return fail(td.failure, td.why + ", " + at(k, t));
  WalkStep& st = out_.steps.back();
  st.impact_behaviour = td.behaviour;
  st.impact_energy_loss = td.energy_loss;
  st.impulse1 = td.impulse1;
  st.impulse2 = td.impulse2;
  st.double_support = td.double_support_follows;
  y.head<5>() = td.q_plus;
  y.segment<5>(5) = td.qd_plus;
  return true;
}

bool Walker::doubleSupport(double& t, Eigen::VectorXd& y, int k) {
  ss_ = false;
  ds_ = dsReference(sys_, t, y.head<5>(), y.segment<5>(5));
  const CvodeIntegrator::Result r = phase(t, y, k);
  t = r.t;
  y = r.y;
  out_.steps.back().t_liftoff = t;
  if (r.root == kRearNormal || r.root == kFrontNormal)
    return fail(WalkOutcome::StanceLiftOff,
                "a foot's normal force < 0 in double support, " + at(k, t));
  if (r.root < 0 && req_.ds_control == DsAlphaControl::TimeOptimal)
    return fail(WalkOutcome::Fell, "alpha did not reach alpha_fDS in double support, " + at(k, t));
  if (r.root >= kRearSlipForward)
    return fail(WalkOutcome::Slipped,
                "a foot left its friction cone in double support, " + at(k, t));
  return true;
}

WalkResult Walker::run() {
  Eigen::VectorXd y(kClosedLoopStateSize);
  const Vec5 q0 = mo_.q_iSS + req_.dq0;
  Vec5 qs;  // q*(α) = ∂q/∂α on the virtual constraints
  qs(0) = 1.0;
  for (int j = 0; j < 4; ++j) qs(j + 1) = mo_.ss_path[j](q0(0)).first;
  y << q0, qs * (mo_.alphadot_iSS + req_.dalphad0), 0.0, 0.0;
  if (req_.use_initial_state) y << req_.q_init, req_.qd_init, 0.0, 0.0;
  double t = 0.0;
  for (int k = 0; k < req_.steps; ++k) {
    startStep(t, y, k);
    if (!walkStep(t, y, k)) break;
    endStep(y);
    out_.q_end = y.head<5>();
    out_.qd_end = y.segment<5>(5);
  }
  return out_;
}

// One step's phases. A step CVODE cannot integrate (measured: a perturbed step of
// configs/gait/chevallereau_aoustin_0.75.yaml in the margin search, 10⁵ CVODE steps before the
// next output) ends the walk like any other failure, so that a margin search or a map counts it
// as not walked.
bool Walker::walkStep(double& t, Eigen::VectorXd& y, int k) {
  try {
    if (!singleSupport(t, y, k)) return false;
    if (!out_.steps.back().double_support) {
      out_.steps.back().t_liftoff = t;
      return true;
    }
    return doubleSupport(t, y, k);
  } catch (const IntegrationError& e) {
    return fail(WalkOutcome::IntegrationFailed, std::string(e.what()) + ", " + at(k, e.time()));
  }
}

}  // namespace

void configureForGait(const GaitOptions& o, WalkRequest& r) {
  r.friction_coefficient = o.friction_coefficient;
  r.plant_friction_coefficient = o.friction_coefficient;
  r.full_torque_envelope = o.full_torque_envelope;
  r.min_normal_force = o.min_normal_force;
  r.touchdown_by_foot_height = true;
  r.hold_references_past_fss = !o.parameterisation.landsWithImpact();
}

double stepEnergyBalanceError(const WalkStep& s) {
  const double scale = std::max({std::abs(s.energy_start), std::abs(s.step_motor_work), 1.0});
  return (s.energy_end - s.energy_start -
          (s.step_motor_work - s.step_friction_loss - s.impact_energy_loss)) /
         scale;
}

WalkResult simulateWalk(const GaitEvaluation<double>& e, const Model& controller,
                        const Model& plant, const WalkRequest& request,
                        const TouchdownMap& touchdown) {
  Walker w(e, controller, plant, request, touchdown);
  return w.run();
}

}  // namespace gaitopt
