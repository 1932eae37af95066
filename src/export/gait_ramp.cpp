#include "gaitopt/export/gait_ramp.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "gaitopt/gait/evaluator_impl.hpp"
#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {
namespace {

using StepPtr = std::shared_ptr<const GaitEvaluation<double>>;

// The step's DS with α from alpha0 at rate v0 to alpha1 at rate v1 along the DS polynomials
// (3.3), α(t) the cubic (3.27) over T = duration_factor · 2Δα / (v0 + v1): factor 1 cancels
// its cubic term (constant α̈), a smaller one shifts the acceleration towards the start.
StepPtr withDsMotion(const GaitEvaluation<double>& e, double alpha0, double v0, double alpha1,
                     double v1, double duration_factor = 1.0) {
  auto out = std::make_shared<GaitEvaluation<double>>(e);
  const double T = duration_factor * 2.0 * (alpha1 - alpha0) / (v0 + v1);
  out->motion.ds_alpha = cubicHermite(0.0, alpha0, v0, T, alpha1, v1);
  out->motion.T_DS = T;
  out->T_DS = T;
  return out;
}

// The gait's step with the SS started at α̇_iSS = a: the same path, its own zero dynamics.
StepPtr stepAtRate(const GaitEvaluator& ev, const GaitParameters& p, double a) {
  GaitParameters q = p;
  q(kAlphadotISS) = a;
  auto e = std::make_shared<GaitEvaluation<double>>(ev.evaluate(q));
  // (3.56) saturates α̇_iSS when the step would fall back: the requested rate is not walkable.
  if (!e->motion_computed || std::abs(e->motion.alphadot_iSS - a) > 1e-12 * std::abs(a))
    throw InfeasibleRamp("ramp step starting at alphad = " + formatDouble(a) +
                         " rad/s falls back before touchdown (3.44): its SS needs alphad_iSS <= " +
                         formatDouble(e->motion.alphadot_iSS) + " rad/s");
  return e;
}

double touchdownRate(const GaitEvaluation<double>& e) { return e.motion.ds_alpha(0.0).first; }

// Stretches of the standing start's and the stop's DS tried in turn: starting or stopping
// needs |α̈| = v² / (2 Δα), too much for the friction cone over the gait's own DS range, so
// these DS continue the DS polynomials (3.3) before α_iDS (start: the hip further back) or
// past α_fDS (stop), the shortest extension whose samples all hold.
// Each stretch is tried with the durations factors in turn (see withDsMotion).
constexpr std::array<double, 9> kStretches{1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 5.0, 6.0};
constexpr std::array<double, 11> kDurationFactors{1.0, 0.9, 0.8, 0.75, 0.7, 0.65, 0.6, 0.55, 0.5, 1.2, 1.4};
constexpr double kCheckRate = 1000.0;  // Hz

template <class MakeStep>
WalkStepMotion shortestFeasible(const GaitEvaluator& ev, const std::vector<ConstraintMaximum>& baseline,
                                const MakeStep& make, const std::string& what) {
  for (double stretch : kStretches)
    for (double factor : kDurationFactors) {
      const std::vector<WalkStepMotion> one{make(stretch, factor)};
      const auto maxima = sampleConstraintMaxima(ev, one, sampleWalk(ev, one, kCheckRate));
      if (violations(maxima, baseline).empty()) return one.front();
    }
  throw InfeasibleRamp("no " + what + " holds the constraints along up to " +
                       formatDouble(kStretches.back()) +
                       " times the gait's DS range (the friction cone bounds α̈ and the rear "
                       "leg runs out of reach)");
}

}  // namespace

std::vector<ConstraintMaximum> gaitBaseline(const GaitEvaluator& ev,
                                            const std::shared_ptr<const GaitEvaluation<double>>& gait) {
  const std::vector<WalkStepMotion> one{{gait, true}};
  return sampleConstraintMaxima(ev, one, sampleWalk(ev, one, kBaselineRate));
}

std::vector<ConstraintMaximum> violations(const std::vector<ConstraintMaximum>& maxima,
                                          const std::vector<ConstraintMaximum>& baseline) {
  std::vector<ConstraintMaximum> out;
  for (const ConstraintMaximum& c : maxima) {
    const auto b = std::find_if(baseline.begin(), baseline.end(),
                                [&](const auto& x) { return x.name == c.name; });
    const double allowed = std::max(0.0, b == baseline.end() ? 0.0 : b->value) + kRampTolerance;
    if (!(c.value <= allowed)) out.push_back(c);
  }
  return out;
}

std::vector<double> rampStartRates(double a_star, double a_slow, const RampRequest& r) {
  // Linear in the SS start kinetic energy, ∝ α̇² along the fixed path.
  const auto rate = [&](double fraction) {
    return -std::sqrt(a_slow * a_slow + (a_star * a_star - a_slow * a_slow) * fraction);
  };
  std::vector<double> rates;
  for (int k = 0; k < r.steps_in; ++k) rates.push_back(rate(static_cast<double>(k) / r.steps_in));
  rates.insert(rates.end(), r.cyclic_steps, a_star);
  for (int k = 1; r.stop && k <= r.steps_out; ++k)
    rates.push_back(rate(1.0 - static_cast<double>(k) / r.steps_out));
  return rates;
}

double slowestStartRate(const GaitEvaluator& ev, const GaitParameters& p) {
  GaitParameters q = p;
  q(kAlphadotISS) = 0.0;  // saturated by (3.56) to the slowest start that does not fall back
  const GaitEvaluation<double> e = ev.evaluate(q);
  if (!e.motion_computed) throw InfeasibleRamp("the gait's step is undefined");
  return e.motion.alphadot_iSS;
}

std::vector<WalkStepMotion> rampedWalk(const GaitEvaluator& ev, const GaitParameters& p,
                                       const GaitEvaluation<double>& cyclic,
                                       const RampRequest& r) {
  if (!ev.options().parameterisation.hasDoubleSupport())
    throw InfeasibleRamp("a ramp needs a gait with double support (the standing start and stop "
                         "are double supports)");
  if (!cyclic.motion_computed) throw InfeasibleRamp("the gait's step is undefined");
  const double a_star = cyclic.motion.alphadot_iSS;
  const double a_slow = std::max(a_star, slowestStartRate(ev, p));
  const std::vector<double> rates = rampStartRates(a_star, a_slow, r);
  const auto ss_step = [&](double a) {
    return a == a_star ? std::make_shared<GaitEvaluation<double>>(cyclic) : stepAtRate(ev, p, a);
  };
  const StepPtr cyclic_step = ss_step(a_star);
  const std::vector<ConstraintMaximum> baseline = gaitBaseline(ev, cyclic_step);
  std::vector<WalkStepMotion> walk;
  const double da = p(kAlphaFDS) - p(kAlphaIDS);
  const StepPtr first = ss_step(rates.front());
  walk.push_back(shortestFeasible(
      ev, baseline,
      [&](double stretch, double factor) {
        return WalkStepMotion{withDsMotion(*first, p(kAlphaFDS) - stretch * da, 0.0,
                                           p(kAlphaFDS), rates.front(), factor),
                              false};
      },
      "start from rest to alphad_iSS = " + formatDouble(rates.front()) + " rad/s"));
  for (std::size_t k = 0; k < rates.size(); ++k) {
    const double next = k + 1 < rates.size() ? rates[k + 1] : r.stop ? 0.0 : a_star;
    if (rates[k] == a_star && next == a_star) {  // the cycle itself, with the gait's own DS
      walk.push_back({cyclic_step, true});
      continue;
    }
    const StepPtr ss = ss_step(rates[k]);
    const double v0 = touchdownRate(*ss);
    if (next != 0.0) {
      walk.push_back({withDsMotion(*ss, p(kAlphaIDS), v0, p(kAlphaFDS), next), true});
      continue;
    }
    walk.push_back(shortestFeasible(
        ev, baseline,
        [&](double stretch, double factor) {
          return WalkStepMotion{
              withDsMotion(*ss, p(kAlphaIDS), v0, p(kAlphaIDS) + stretch * da, 0.0, factor),
              true};
        },
        "stop to rest from the touchdown rate " + formatDouble(v0) + " rad/s"));
  }
  return walk;
}

std::vector<PlannedSample> sampleWalk(const GaitEvaluator& ev, const std::vector<WalkStepMotion>& steps,
                                   double rate) {
  std::vector<double> start{0.0};
  for (const WalkStepMotion& s : steps)
    start.push_back(start.back() + (s.single_support ? s.evaluation->T_SS : 0.0) +
                    s.evaluation->motion.T_DS);
  const long n = static_cast<long>(std::floor(start.back() * rate + 1e-9));
  std::vector<PlannedSample> out;
  std::size_t k = 0;
  int ss_before = 0;  // SS phases before step k: the stance foot of step k is d · ss_before
  for (long i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) / rate;
    while (k + 1 < steps.size() && t >= start[k + 1] - 1e-12 * (start[k + 1] - start[k])) {
      ss_before += steps[k].single_support ? 1 : 0;
      ++k;
    }
    const WalkStepMotion& s = steps[k];
    const GaitMotion<double>& mo = s.evaluation->motion;
    const double local = std::max(0.0, t - start[k]);
    const bool ss = s.single_support && local < mo.T_SS;
    const double t_ds = std::min(local - (s.single_support ? mo.T_SS : 0.0), mo.T_DS);
    // In DS leg 1 is the front leg, the stance leg of the next SS.
    const int foot = ss_before + (ss || !s.single_support ? 0 : 1);
    out.push_back({t, static_cast<int>(k), mo.d * foot, foot % 2 == 0,
                   ss ? sampleTrajectoryAt(ev, *s.evaluation, Phase::SingleSupport, local)
                      : sampleTrajectoryAt(ev, *s.evaluation, Phase::DoubleSupport, t_ds)});
  }
  return out;
}

std::vector<ConstraintMaximum> sampleConstraintMaxima(const GaitEvaluator& ev,
                                                      const std::vector<WalkStepMotion>& steps,
                                                      const std::vector<PlannedSample>& samples) {
  const GaitOptions& o = ev.options();
  const RobotParams& robot = ev.model().robot;
  const ConstraintLayout& layout = ev.layout();
  std::vector<ConstraintMaximum> out;
  const auto update = [&](int group, const char* unit, double g, const PlannedSample& s) {
    const std::string& name = layout[group].name;
    auto it = std::find_if(out.begin(), out.end(), [&](const auto& m) { return m.name == name; });
    if (it == out.end()) it = out.insert(out.end(), ConstraintMaximum{name, unit, g, s.t, s.step});
    if (g > it->value) *it = ConstraintMaximum{name, unit, g, s.t, s.step};
  };
  for (const PlannedSample& s : samples) {
    const TrajectoryRow& r = s.row;
    const bool ss = r.phase == Phase::SingleSupport;
    for (int j = 0; j < 4; ++j)  // (3.46), (3.47)
      update(ss ? kTorqueSS : kTorqueDS, "N*m", std::abs(r.gamma_star(j)) - r.gamma_max(j), s);
    const std::array<double, 4> angles = {r.q(1), r.q(2), r.q(2) + r.q(3), r.q(4)};  // (3.42)
    for (int j = 0; j < 4; ++j) {
      const bool knee = j == 0 || j == 3;
      const double lo = knee ? robot.limits.knee_min : robot.limits.hip_min;
      const double hi = knee ? robot.limits.knee_max : robot.limits.hip_max;
      update(ss ? kJointLimitsSS : kJointLimitsDS, "rad",
             std::max(angles[j] - hi, lo - angles[j]) + o.joint_limit_margin, s);
    }
    for (const Vec2* R : ss ? std::vector<const Vec2*>{&r.R1} : std::vector{&r.R1, &r.R2}) {
      update(ss ? kFrictionConeSS : kFrictionConeDS, "N",
             std::abs((*R)(0)) - o.friction_coefficient * (*R)(1), s);  // (3.48)
      update(ss ? kNormalForceSS : kNormalForceDS, "N", o.min_normal_force - (*R)(1), s);
    }
    const GaitMotion<double>& mo = steps[s.step].evaluation->motion;
    if (!ss) {  // (3.41): the rear foot within reach of the hip
      const double L = robot.l4 + robot.l5;
      const double rho2 = detail::rearFootFromHip(ev.model(), r.q(0), r.q(1), mo.d).squaredNorm();
      update(kDsReachMax, "m^2", rho2 - L * L + o.reach_margin, s);
      update(kDsReachMin, "m^2", o.reach_margin - rho2, s);
    }
    if (!(r.q.allFinite() && r.gamma_star.allFinite() && r.R1.allFinite() && r.R2.allFinite()))
      update(kDsReachMax, "m^2", std::numeric_limits<double>::infinity(), s);
    if (ss && r.t > 0.0 && r.t < mo.T_SS)  // (3.49) on the open interval, as the evaluator
      update(kClearance, "m", r.clearance - r.foot2(1), s);
    if (!ss) {  // (3.43); a DS starting or ending at rest holds α̇ ≤ 0 only
      const bool rest = std::abs(mo.ds_alpha(0.0).first) < 1e-12 ||
                        std::abs(mo.ds_alpha(mo.T_DS).first) < 1e-12;
      update(kDsMonotone, "rad/s", r.qd(0) - (rest ? 0.0 : o.ds_alphadot_max), s);
    }
  }
  return out;
}

}  // namespace gaitopt
