#include "gaitopt/sim/stability_margins.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "gaitopt/model/chain_kinematics.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/sim/poincare_sensitivity.hpp"

namespace gaitopt {
namespace {

// Largest v in [0, upper] with passes(v) (assumed monotone), to `resolution`.
Margin bisect(const std::function<bool(double, std::string&)>& passes, double upper,
              double resolution) {
  Margin m;
  m.resolution = resolution;
  std::string why;
  if (passes(upper, why)) {
    m.value = upper;
    m.bracket_reached = true;
    return m;
  }
  m.limit = why;
  double lo = 0.0, hi = upper;
  while (hi - lo > resolution) {
    const double mid = 0.5 * (lo + hi);
    if (passes(mid, why)) {
      lo = mid;
    } else {
      hi = mid;
      m.limit = why;
    }
  }
  m.value = lo;
  return m;
}

WalkResult walkFrom(const GaitEvaluation<double>& e, const Model& c, const Model& p,
                    const WalkRequest& base, const Eigen::VectorXd& x, int steps,
                    const TouchdownMap& td) {
  WalkRequest req = base;
  req.steps = steps;
  req.use_initial_state = true;
  req.q_init = x.head<5>();
  req.qd_init = x.tail<5>();
  req.sample_rate = 1.0;
  return simulateWalk(e, c, p, req, td);
}

}  // namespace

bool pushRecovered(const GaitEvaluation<double>& e, const Model& model, const WalkRequest& base,
                   double dv, const MarginRequest& mr, const TouchdownMap& td, std::string& why) {
  const GaitMotion<double>& mo = e.motion;
  const Eigen::VectorXd cycle = walkingCycleState(mo);
  const double alpha_mid = 0.5 * (mo.q_iSS(0) + mo.alpha_fSS);
  const ClosedLoop loop = walkingClosedLoop(mo, model, model, base);
  const PhaseEnd mid = flowWithSensitivity(
      walkingSingleSupport(loop, alpha_mid, false),
      {0.0, cycle, Eigen::MatrixXd(10, 0)}, 10.0, base.tolerances);
  if (!mid.event) throw std::runtime_error("push margin: the cycle does not reach mid SS");
  Eigen::VectorXd x = mid.state.x;
  const Vec5 q = x.head<5>(), qd = x.tail<5>();
  // Impulse P at the hip along x: Δq̇ = A⁻¹ Jₓᵀ P with Jₓ Δq̇ = Δv.
  const Eigen::Matrix<double, 1, 5> Jx =
      chainPointJacobian(model, model.pinned.hip, chainState(model, q, qd)).row(0);
  const Vec5 AinvJ = pinnedTerms(model, q, qd).A.ldlt().solve(Jx.transpose());
  x.tail<5>() += AinvJ * (dv / Jx.dot(AinvJ));
  const WalkResult r = walkFrom(e, model, model, base, x, mr.steps, td);
  if (r.outcome != WalkOutcome::Completed) {
    why = std::string(outcomeName(r.outcome)) + ": " + r.message;
    return false;
  }
  Eigen::VectorXd end(10);
  end << r.q_end, r.qd_end;
  const double distance = (end - cycle).lpNorm<Eigen::Infinity>();
  why = "not back on the cycle after " + std::to_string(mr.steps) + " steps (distance " +
        std::to_string(distance) + ")";
  return distance <= mr.tolerance;
}

Margin largestPush(const GaitEvaluation<double>& e, const Model& model, const WalkRequest& base,
                   int direction, const MarginRequest& mr, const TouchdownMap& td) {
  return bisect(
      [&](double v, std::string& why) {
        return pushRecovered(e, model, base, direction * v, mr, td, why);
      },
      mr.push_upper, mr.push_resolution);
}

bool payloadTolerated(const GaitEvaluation<double>& e, const RobotParams& robot,
                      const ModelOptions& options, const WalkRequest& base, double mass,
                      const MarginRequest& mr, const TouchdownMap& td, std::string& why) {
  RobotParams heavy = robot;
  heavy.mass[2] += mass;  // a point mass at the trunk's CoM: the trunk inertia is unchanged
  const Model controller = buildModel(robot, options), plant = buildModel(heavy, options);
  const WalkResult r = walkFrom(e, controller, plant, base, walkingCycleState(e.motion),
                                mr.steps, td);
  if (r.outcome != WalkOutcome::Completed) {
    why = std::string(outcomeName(r.outcome)) + ": " + r.message;
    return false;
  }
  const double change = std::abs(r.steps.back().alphad_start - r.qd_end(0));
  why = "alphad at SS start still changing by " + std::to_string(change) + " rad/s per step";
  return change <= mr.tolerance;
}

Margin largestPayload(const GaitEvaluation<double>& e, const RobotParams& robot,
                      const ModelOptions& options, const WalkRequest& base,
                      const MarginRequest& mr, const TouchdownMap& td) {
  return bisect(
      [&](double m, std::string& why) {
        return payloadTolerated(e, robot, options, base, m, mr, td, why);
      },
      mr.payload_upper, mr.payload_resolution);
}

bool slopeWalked(const GaitEvaluation<double>& e, const Model& model, const WalkRequest& base,
                 double slope, const MarginRequest& mr, const TouchdownMap& td, std::string& why) {
  WalkRequest req = base;
  req.ground_slope = slope;
  const WalkResult r = walkFrom(e, model, model, req, walkingCycleState(e.motion), mr.steps, td);
  why = std::string(outcomeName(r.outcome)) + ": " + r.message;
  return r.outcome == WalkOutcome::Completed;
}

Margin largestSlope(const GaitEvaluation<double>& e, const Model& model, const WalkRequest& base,
                    int direction, const MarginRequest& mr, const TouchdownMap& td) {
  return bisect(
      [&](double s, std::string& why) {
        return slopeWalked(e, model, base, direction * s, mr, td, why);
      },
      mr.slope_upper, mr.slope_resolution);
}

}  // namespace gaitopt
