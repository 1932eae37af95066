#include "gaitopt/control/gait_ramp.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <nlopt.hpp>
#include <optional>
#include <tuple>

#include "gaitopt/gait/boundary_geometry.hpp"
#include "gaitopt/gait/constraints/clearance.hpp"
#include "gaitopt/gait/constraints/contact.hpp"
#include "gaitopt/gait/constraints/ds_monotone.hpp"
#include "gaitopt/gait/constraints/joint_limits.hpp"
#include "gaitopt/gait/constraints/reach.hpp"
#include "gaitopt/gait/constraints/torque_envelope.hpp"
#include "gaitopt/math/decimal.hpp"

namespace gaitopt {
namespace {

using StepPtr = std::shared_ptr<const GaitEvaluation<double>>;

// What a sample of constraint `name` may reach: the gait's own level, if positive (gaitBaseline).
double allowedMaximum(const std::vector<ConstraintMaximum>& baseline, const std::string& name) {
  const auto b = std::find_if(baseline.begin(), baseline.end(),
                              [&](const auto& x) { return x.name == name; });
  return std::max(0.0, b == baseline.end() ? 0.0 : b->value) * (1.0 + kRampRelativeTolerance) +
         kRampTolerance;
}

// The step's DS with α from alpha0 at rate v0 to alpha1 at rate v1 along the DS polynomials
// (3.3), α(t) the cubic (3.27) over T = duration_factor · 2Δα / (v0 + v1): factor 1 cancels
// its cubic term (constant α̈), a larger one shifts the deceleration towards the touchdown.
StepPtr withDsMotion(const GaitEvaluation<double>& e, double alpha0, double v0, double alpha1,
                     double v1, double duration_factor) {
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

// A DS at rest at one end (the standing start or the stop), with its own path: δ1(α), δ2(α)
// the cubic Hermite (3.26) between the junction with the walk (value and slope of the gait's
// DS polynomial there, so q and q̇ are continuous) and a free rest configuration, and α(t) the
// cubic (3.27) between the junction rate and rest. The gait's own DS range is far too short
// to start or stop within the friction cone (|α̈| = v² / (2 Δα)), so the rest configuration
// lies Δα beyond it, on a path of its own.
struct RestDsDesign {
  double range = 0.1;       // |α_rest − α_junction| [rad]
  double delta1 = 0.0;      // δ1 at rest [rad]
  double theta3 = 0.0;      // trunk angle at rest [rad]
  double slope1 = 0.0;      // dδ1/dα at rest
  double slope2 = 1.0;      // dδ2/dα at rest (1 + slope1: the trunk keeps its angle)
  double duration = 1.0;    // T / (2 Δα / v): 1 is constant α̈, less shifts it to the start
};
constexpr int kMaxSearchEvaluations = 3000;

// `start`: rest → junction at the end of the DS (α_fDS, rate v); otherwise junction at the DS
// start (α_iDS, rate v) → rest.
StepPtr restDs(const GaitEvaluation<double>& e, bool start, double v, const RestDsDesign& x) {
  auto out = std::make_shared<GaitEvaluation<double>>(e);
  GaitMotion<double>& mo = out->motion;
  const double aj = start ? mo.ds_alpha(mo.T_DS).value : mo.ds_alpha(0.0).value;
  const PolyValue<double> d1 = e.motion.ds_delta1(aj), d2 = e.motion.ds_delta2(aj);
  // α decreases while walking: the rest is behind (start) or ahead of (stop) the junction.
  const double ar = start ? aj + x.range : aj - x.range;
  const double d2r = delta2FromTheta3(ar, x.delta1, x.theta3);
  mo.ds_delta1 = PathCurve<double>(cubicHermite(aj, d1.value, d1.first, ar, x.delta1, x.slope1), aj, ar);
  mo.ds_delta2 = PathCurve<double>(cubicHermite(aj, d2.value, d2.first, ar, d2r, x.slope2), aj, ar);
  const double T = x.duration * 2.0 * x.range / std::abs(v);
  mo.ds_alpha = start ? cubicHermite(0.0, ar, 0.0, T, aj, v) : cubicHermite(0.0, aj, v, T, ar, 0.0);
  mo.T_DS = T;
  out->T_DS = T;
  return out;
}

constexpr double kSearchRate = 500.0;  // Hz, the samples the searches hold
constexpr double kConfirmRate = 2000.0;  // Hz, the samples a design found is confirmed at

// The maxima over a walk fragment's samples at `rate` and at the exact start and end of its
// last DS: touchdown and lift-off (or rest) are often the worst samples and fall between the
// regular ones.
std::vector<ConstraintMaximum> maximaWithEnd(const GaitEvaluator& ev,
                                             const std::vector<WalkStepMotion>& walk, double rate) {
  std::vector<PlannedSample> samples = sampleWalk(ev, walk, rate);
  const GaitEvaluation<double>& last = *walk.back().evaluation;
  for (double t : {0.0, last.motion.T_DS}) {
    PlannedSample end = samples.back();
    end.row = sampleTrajectoryAt(ev, last, Phase::DoubleSupport, t);
    samples.push_back(end);
  }
  return sampleConstraintMaxima(ev, walk, samples);
}
// Margin kept in the search, as a fraction of each constraint's scale, so that the samples
// at the export rate (between the search's) hold too.
constexpr double kSearchMargin = 0.02;

double unitScale(const std::string& unit) {
  if (unit == "N") return 50.0;
  if (unit == "N m") return 10.0;
  if (unit == "m^2") return 0.01;
  if (unit == "m") return 0.005;
  return 0.05;  // rad, rad/s
}

// Σ max(0, excess / scale + margin) over the constraints: 0 when every sample holds with the
// margin.
double merit(const std::vector<ConstraintMaximum>& maxima,
             const std::vector<ConstraintMaximum>& baseline) {
  double sum = 0.0;
  for (const ConstraintMaximum& c : maxima) {
    const double excess = c.value - allowedMaximum(baseline, c.name);
    const double scaled = excess / unitScale(c.unit) + kSearchMargin;
    sum += std::isfinite(scaled) ? std::max(0.0, scaled) : 1e6;
  }
  return sum;
}

// A design searched over: its variables with bounds, and the walk fragment they make (empty
// when undefined, e.g. a step that falls back).
struct Design {
  std::vector<double> x0, lower, upper;
  std::function<std::vector<WalkStepMotion>(const std::vector<double>&)> make;
};

// The design whose samples hold, by a derivative-free search (the per-sample maxima are not
// smooth in the design: the worst sample moves) from x0; InfeasibleRamp naming the constraint
// that stays violated otherwise.
std::vector<WalkStepMotion> searchDesign(const GaitEvaluator& ev,
                                         const std::vector<ConstraintMaximum>& baseline,
                                         const Design& d, const std::string& what) {
  nlopt::opt opt(nlopt::LN_SBPLX, static_cast<unsigned>(d.x0.size()));
  // The search stops at the first design whose samples hold without the margin at
  // kSearchRate and at kConfirmRate (the margin keeps the merit positive where the gait
  // itself is at a bound).
  std::optional<std::vector<double>> found;
  using Objective = std::function<double(const std::vector<double>&)>;
  Objective f = [&](const std::vector<double>& x) {
    const std::vector<WalkStepMotion> walk = d.make(x);
    if (walk.empty()) return 1e6;
    const std::vector<ConstraintMaximum> maxima = maximaWithEnd(ev, walk, kSearchRate);
    if (violations(maxima, baseline).empty() &&
        violations(maximaWithEnd(ev, walk, kConfirmRate), baseline).empty()) {
      found = x;
      opt.force_stop();
    }
    return merit(maxima, baseline);
  };
  opt.set_lower_bounds(d.lower);
  opt.set_upper_bounds(d.upper);
  opt.set_min_objective(
      [](unsigned n, const double* x, double*, void* data) {
        return (*static_cast<Objective*>(data))(std::vector<double>(x, x + n));
      },
      &f);
  opt.set_maxeval(kMaxSearchEvaluations);
  std::vector<double> x = d.x0;
  double value = 0.0;
  try {
    opt.optimize(x, value);
  } catch (const std::exception&) {  // forced stop or roundoff-limited: x holds the best point
  }
  if (found) x = *found;
  const std::vector<WalkStepMotion> walk = d.make(x);
  if (walk.empty()) throw InfeasibleRamp("no " + what + " is defined (its step falls back)");
  const auto bad = violations(maximaWithEnd(ev, walk, kSearchRate), baseline);
  if (bad.empty()) return walk;
  const auto worst = std::max_element(bad.begin(), bad.end(), [](const auto& a, const auto& b) {
    return a.value / unitScale(a.unit) < b.value / unitScale(b.unit);
  });
  throw InfeasibleRamp("no " + what + " holds the constraints: " + worst->name +
                       " still violated by " + formatDouble(worst->value) + " " + worst->unit +
                       " (the best design of a search of up to " +
                       std::to_string(kMaxSearchEvaluations) + ")");
}

// The rest DS variables (RestDsDesign) with their bounds, appended to `d`.
void appendRestDs(Design& d, const RestDsDesign& g) {
  const std::vector<double> x{g.range, g.delta1, g.theta3, g.slope1, g.slope2, g.duration};
  const std::vector<double> lo{0.02, g.delta1 - 0.8, g.theta3 - 0.4, -4.0, -4.0, 0.4};
  const std::vector<double> hi{0.6, g.delta1 + 0.8, g.theta3 + 0.4, 4.0, 4.0, 2.5};
  d.x0.insert(d.x0.end(), x.begin(), x.end());
  d.lower.insert(d.lower.end(), lo.begin(), lo.end());
  d.upper.insert(d.upper.end(), hi.begin(), hi.end());
}
RestDsDesign restDsAt(const std::vector<double>& v, std::size_t i) {
  return {v[i], v[i + 1], v[i + 2], v[i + 3], v[i + 4], v[i + 5]};
}

// The DS between two walking steps along the gait's DS path, from the touchdown rate v0 to the
// next step's start rate v1: with constant α̈ the rear foot would still be pushed down hard
// at lift-off, so the duration factor (withDsMotion) is the best of a scan over
// [kDurationMin, kDurationMax], the first whose samples all hold.
constexpr double kDurationMin = 0.8, kDurationMax = 1.6;
constexpr int kDurationScan = 33;
WalkStepMotion transitionDs(const GaitEvaluator& ev, const std::vector<ConstraintMaximum>& baseline,
                            const GaitEvaluation<double>& e, double v0, double v1) {
  const double a0 = e.motion.ds_alpha(0.0).value, a1 = e.motion.ds_alpha(e.motion.T_DS).value;
  double best = std::numeric_limits<double>::infinity();
  WalkStepMotion chosen;
  for (int i = 0; i < kDurationScan && best > 0.0; ++i) {
    const double factor = kDurationMin + (kDurationMax - kDurationMin) * i / (kDurationScan - 1);
    const std::vector<WalkStepMotion> one{{withDsMotion(e, a0, v0, a1, v1, factor), true}};
    const double m = merit(maximaWithEnd(ev, one, kSearchRate), baseline);
    if (m < best) std::tie(best, chosen) = std::make_pair(m, one.front());
  }
  return chosen;
}

// The first guess: rest Δα = 0.1 rad beyond the junction with the junction's knee and trunk.
RestDsDesign restGuess(const GaitEvaluation<double>& e, bool start) {
  const GaitMotion<double>& mo = e.motion;
  const double aj = start ? mo.ds_alpha(mo.T_DS).value : mo.ds_alpha(0.0).value;
  const double d1 = mo.ds_delta1(aj).value, d2 = mo.ds_delta2(aj).value;
  RestDsDesign x;
  x.delta1 = d1;
  x.theta3 = aj + d1 - d2 + 0.5 * M_PI;  // inverse of delta2FromTheta3
  return x;
}

// The standing start: a DS from rest to the first SS start (rate a) on a path of its own.
WalkStepMotion standingStart(const GaitEvaluator& ev,
                             const std::vector<ConstraintMaximum>& baseline,
                             const GaitEvaluation<double>& first, double a) {
  Design d;
  appendRestDs(d, restGuess(first, true));
  d.make = [&](const std::vector<double>& x) {
    return std::vector<WalkStepMotion>{{restDs(first, true, a, restDsAt(x, 0)), false}};
  };
  return searchDesign(ev, baseline, d, "start from rest to alphad_iSS = " + formatDouble(a) +
                                           " rad/s").front();
}

// The gait parameters a ramp-out step redesigns: its SS keeps its start (continuous with the
// previous DS) and changes its path and touchdown, so that the robot lands with the CoM far
// enough behind the front foot and slow enough to be slowed or stopped within the friction
// cone and with both feet loaded (the gait's own touchdown is too fast to stop before the CoM
// passes the front foot).
constexpr std::array<int, 9> kRampOutStepFree{kAlphaIDS,  kDelta1IDS, kTheta3IDS,
                                               kDelta1Int, kTheta3Int, kX2rInt,
                                               kZ2Int,     kDelta1sFSS, kDelta2sFSS};
double rampOutHalfWidth(int i) {
  if (i == kX2rInt || i == kZ2Int) return 0.05;          // m
  if (i == kDelta1sFSS || i == kDelta2sFSS) return 1.0;  // rad/rad
  return 0.15;                                           // rad
}

// A ramp-out step: its SS from rate `a` on a path of its own (kRampOutStepFree), then the DS
// to the next step's start rate `next` along its own DS polynomials (duration factor free,
// withDsMotion), or, when next = 0, a DS to rest on a path of its own.
WalkStepMotion rampOutStep(const GaitEvaluator& ev, const std::vector<ConstraintMaximum>& baseline,
                           const GaitParameters& p, const GaitEvaluation<double>& ss, double next) {
  const double a = ss.motion.alphadot_iSS;
  Design d;
  for (int i : kRampOutStepFree) {
    d.x0.push_back(p(i));
    d.lower.push_back(p(i) - rampOutHalfWidth(i));
    d.upper.push_back(p(i) + rampOutHalfWidth(i));
  }
  const std::size_t n = kRampOutStepFree.size();
  if (next == 0.0) {
    appendRestDs(d, restGuess(ss, false));
  } else {
    d.x0.push_back(1.0);
    d.lower.push_back(kDurationMin);
    d.upper.push_back(kDurationMax);
  }
  d.make = [&](const std::vector<double>& x) {
    GaitParameters q = p;
    for (std::size_t k = 0; k < n; ++k) q(kRampOutStepFree[k]) = x[k];
    q(kAlphadotISS) = a;
    const GaitEvaluation<double> e = ev.evaluate(q);
    std::vector<WalkStepMotion> out;
    if (!e.motion_computed || e.numerically_undefined || e.motion.alphadot_iSS != a) return out;
    const double v0 = touchdownRate(e);
    const double a0 = e.motion.ds_alpha(0.0).value, a1 = e.motion.ds_alpha(e.motion.T_DS).value;
    out.push_back({next == 0.0 ? restDs(e, false, v0, restDsAt(x, n))
                               : withDsMotion(e, a0, v0, a1, next, x[n]),
                   true});
    return out;
  };
  const std::string what =
      next == 0.0 ? "stop to rest" : "slowing to alphad_iSS = " + formatDouble(next) + " rad/s";
  return searchDesign(ev, baseline, d, what + " after an SS started at alphad_iSS = " +
                                           formatDouble(a) + " rad/s").front();
}

}  // namespace

std::vector<ConstraintMaximum> gaitBaseline(const GaitEvaluator& ev,
                                            const std::shared_ptr<const GaitEvaluation<double>>& gait) {
  return maximaWithEnd(ev, {{gait, true}}, kBaselineRate);
}

std::vector<ConstraintMaximum> violations(const std::vector<ConstraintMaximum>& maxima,
                                          const std::vector<ConstraintMaximum>& baseline) {
  std::vector<ConstraintMaximum> out;
  for (const ConstraintMaximum& c : maxima)
    if (!(c.value <= allowedMaximum(baseline, c.name))) out.push_back(c);
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
  std::vector<WalkStepMotion> walk{
      standingStart(ev, baseline, *ss_step(rates.front()), rates.front())};
  for (std::size_t k = 0; k < rates.size(); ++k) {
    const double next = k + 1 < rates.size() ? rates[k + 1] : r.stop ? 0.0 : a_star;
    if (rates[k] == a_star && next == a_star) {  // the cycle itself, with the gait's own DS
      walk.push_back({cyclic_step, true});
      continue;
    }
    const StepPtr ss = ss_step(rates[k]);
    // Ramp-in steps speed up along the gait's path; ramp-out steps need their own.
    if (next != 0.0 && std::abs(next) >= std::abs(rates[k]))
      walk.push_back(transitionDs(ev, baseline, *ss, touchdownRate(*ss), next));
    else
      walk.push_back(rampOutStep(ev, baseline, p, *ss, next));
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
  const auto update = [&](int group, double g, const PlannedSample& s) {
    const std::string& name = layout[group].name;
    const std::string& unit = layout[group].unit;
    auto it = std::find_if(out.begin(), out.end(), [&](const auto& m) { return m.name == name; });
    if (it == out.end()) it = out.insert(out.end(), ConstraintMaximum{name, unit, g, s.t, s.step});
    if (g > it->value) *it = ConstraintMaximum{name, unit, g, s.t, s.step};
  };
  // A pair of rows (upper, lower bound) as one value: the larger.
  const auto larger = [](const std::array<double, 2>& rows) { return std::max(rows[0], rows[1]); };
  for (const PlannedSample& s : samples) {
    const TrajectoryRow& r = s.row;
    const bool ss = r.phase == Phase::SingleSupport;
    for (int j = 0; j < 4; ++j)  // (3.46), (3.47)
      update(ss ? kTorqueSS : kTorqueDS,
             larger(torqueEnvelopeRows(r.gamma_star(j), r.gamma_max(j))), s);
    const std::array<double, 4> angles = jointLimitAngles(r.q);  // (3.42)
    for (int j = 0; j < 4; ++j)
      update(ss ? kJointLimitsSS : kJointLimitsDS,
             larger(jointLimitRows(robot.limits, j, angles[j], o.joint_limit_margin)), s);
    for (const Vec2* R : ss ? std::vector<const Vec2*>{&r.R1} : std::vector{&r.R1, &r.R2}) {
      update(ss ? kFrictionConeSS : kFrictionConeDS, frictionConeExcess(*R, o.friction_coefficient),
             s);
      update(ss ? kNormalForceSS : kNormalForceDS, normalForceRow(*R, o.min_normal_force), s);
    }
    const GaitMotion<double>& mo = steps[s.step].evaluation->motion;
    if (!ss) {  // (3.41): the rear foot within reach of the hip
      const double rho2 = rearFootFromHip(ev.model(), r.q(0), r.q(1), mo.d).squaredNorm();
      const std::array<double, 2> reach = reachRows(rho2, robot.l4 + robot.l5, o.reach_margin);
      update(kDsReachMax, reach[0], s);
      update(kDsReachMin, reach[1], s);
    }
    if (!(r.q.allFinite() && r.gamma_star.allFinite() && r.R1.allFinite() && r.R2.allFinite()))
      update(kDsReachMax, std::numeric_limits<double>::infinity(), s);
    if (ss && r.t > 0.0 && r.t < mo.T_SS)  // (3.49) on the open interval, as the evaluator
      update(kClearance, clearanceRow(r.foot2(1), r.clearance), s);
    if (!ss) {  // (3.43); a DS starting or ending at rest holds α̇ ≤ 0 only
      const bool rest = std::abs(mo.ds_alpha(0.0).first) < 1e-12 ||
                        std::abs(mo.ds_alpha(mo.T_DS).first) < 1e-12;
      update(kDsMonotone, dsMonotoneRow(r.qd(0), rest ? 0.0 : o.ds_alphadot_max), s);
    }
  }
  return out;
}

}  // namespace gaitopt
