#include "gaitopt/sim/zero_dynamics_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gaitopt {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct OneStep {
  bool walked;
  Vec5 q, qd;         // at the next SS start
  double alphad_iDS;  // just after the touchdown map (first DS sample)
  std::string outcome;
};

OneStep walkOneStep(const GaitEvaluation<double>& e, const Model& c, const Model& p,
                    const WalkRequest& base, const TouchdownMap& td, const Vec5& q,
                    const Vec5& qd) {
  WalkRequest req = base;
  req.steps = 1;
  req.use_initial_state = true;
  req.q_init = q;
  req.qd_init = qd;
  req.sample_rate = 1.0;  // phase starts are always recorded
  const WalkResult r = simulateWalk(e, c, p, req, td);
  OneStep s{r.outcome == WalkOutcome::Completed, r.q_end, r.qd_end, kNaN,
            outcomeName(r.outcome)};
  for (const WalkSample& w : r.samples)
    if (!w.single_support) {
      s.alphad_iDS = w.qd(0);
      break;
    }
  return s;
}

// Iterates the closed loop from the virtual constraints at α̇_iSS = v.
ZeroDynamicsPoint follow(const GaitEvaluation<double>& e, const Model& c, const Model& p,
                         const WalkRequest& base, const ZeroDynamicsRequest& zr, double v) {
  const Eigen::VectorXd cycle = walkingCycleState(e.motion);
  const double star = cycle(5);
  Vec5 q = cycle.head<5>(), qd = cycle.tail<5>() * (v / star);
  ZeroDynamicsPoint pt{v, kNaN, kNaN, kNaN, -1, "completed"};
  for (int k = 0; k <= zr.max_steps; ++k) {
    if (pt.steps_to_cycle < 0 && std::abs(qd(0) - star) <= zr.tolerance * std::abs(star))
      pt.steps_to_cycle = k;
    // Two steps at least: the maps need α̇_iSS(k + 1) and α̇_iDS(k + 1).
    if (k == zr.max_steps || (pt.steps_to_cycle >= 0 && k >= 2)) break;
    const OneStep s = walkOneStep(e, c, p, base, zr.touchdown, q, qd);
    if (k == 0) pt.alphad_iDS = s.alphad_iDS;
    if (k == 1) pt.next_alphad_iDS = s.alphad_iDS;
    if (!s.walked) {
      pt.outcome = s.outcome;
      if (pt.steps_to_cycle > k) pt.steps_to_cycle = -1;
      break;
    }
    q = s.q;
    qd = s.qd;
    if (k == 0) pt.next_alphad_iSS = qd(0);
  }
  return pt;
}

// The grid interval around index `centre` whose points satisfy `inside`.
void interval(const std::vector<ZeroDynamicsPoint>& pts, std::size_t centre,
              bool (*inside)(const ZeroDynamicsPoint&), double& low, double& high) {
  low = high = kNaN;
  if (!inside(pts[centre])) return;
  std::size_t a = centre, b = centre;
  while (a > 0 && inside(pts[a - 1])) --a;
  while (b + 1 < pts.size() && inside(pts[b + 1])) ++b;
  low = std::min(pts[a].alphad_iSS, pts[b].alphad_iSS);
  high = std::max(pts[a].alphad_iSS, pts[b].alphad_iSS);
}

}  // namespace

ZeroDynamicsStudy studyZeroDynamics(const GaitEvaluation<double>& e, const Model& c,
                                    const Model& p, const WalkRequest& base,
                                    const ZeroDynamicsRequest& zr) {
  const Eigen::VectorXd cycle = walkingCycleState(e.motion);
  const double star = cycle(5);
  ZeroDynamicsStudy s;
  s.fixed_point = star;
  auto map = [&](double v) {
    const OneStep o = walkOneStep(e, c, p, base, zr.touchdown, cycle.head<5>(), cycle.tail<5>() * (v / star));
    return o.walked ? o.qd(0) : kNaN;
  };
  s.fixed_point_residual = std::abs(map(star) - star);
  const double h = 1e-6 * std::abs(star);
  s.slope = (map(star + h) - map(star - h)) / (2.0 * h);
  s.stable = std::abs(s.slope) < 1.0;  // NaN (a neighbour not walked) is not stable
  // Signed α̇ grid (α̇ < 0 walking forward), from the slowest to the fastest start.
  std::size_t centre = 0;
  for (int i = 0; i < zr.points; ++i) {
    const double u = zr.points > 1 ? 2.0 * i / (zr.points - 1) - 1.0 : 0.0;
    s.points.push_back(follow(e, c, p, base, zr, star * (1.0 + zr.range * u)));
    if (std::abs(s.points[i].alphad_iSS - star) < std::abs(s.points[centre].alphad_iSS - star))
      centre = i;
  }
  s.resolution = zr.points > 1 ? 2.0 * zr.range * std::abs(star) / (zr.points - 1) : 0.0;
  interval(s.points, centre,
           [](const ZeroDynamicsPoint& q) { return q.steps_to_cycle >= 0 && q.steps_to_cycle <= 1; },
           s.one_step_low, s.one_step_high);
  interval(s.points, centre, [](const ZeroDynamicsPoint& q) { return q.steps_to_cycle >= 0; },
           s.global_low, s.global_high);
  return s;
}

}  // namespace gaitopt
