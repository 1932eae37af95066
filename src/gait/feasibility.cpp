#include "gaitopt/gait/feasibility.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gaitopt/gait/summary.hpp"

namespace gaitopt {
namespace {

constexpr double kNone = -std::numeric_limits<double>::infinity();
// Local refinement: around each refined-grid local maximum within this (scaled) band of
// active, the constraints are also evaluated at six points between the refined nodes.
constexpr double kProbeBand = 1e-3;

// Vertex of the parabola through (x0, y0), (x1, y1), (x2, y2) with y1 the largest, kept in
// [min(x0, x2), max(x0, x2)]: the local maximum between refined nodes.
double parabolaVertex(double x0, double y0, double x1, double y1, double x2, double y2) {
  const double d0 = (y1 - y0) / (x1 - x0), d1 = (y2 - y1) / (x2 - x1);
  const double curvature = (d1 - d0) / (x2 - x0);
  if (!(curvature < 0.0)) return x1;
  const double x = 0.5 * (x0 + x1) - d0 / (2.0 * curvature);
  return std::clamp(x, std::min(x0, x2), std::max(x0, x2));
}

// Scans one entry sequence (one per refined grid point) of a phase-wise group.
void scanSequence(const GaitEvaluator& fine, const GaitEvaluation<double>& e,
                  const ConstraintGroup& group, int sub, double threshold,
                  std::vector<double>& maxima, std::vector<double>& probes) {
  const ChebyshevGrid& grid =
      group.phase == ConstraintPhase::SingleSupport ? fine.ssGrid() : fine.dsGrid();
  const int points = group.count / group.per_point;
  const auto value = [&](int i) {
    const int k = group.offset + i * group.per_point + sub;
    return e.state[k] == ConstraintState::NotComputed ? kNone : e.g[k] / group.scale;
  };
  const auto node = [&](int i) { return grid.nodes()[i + group.first_point]; };
  for (int i = 1; i + 1 < points; ++i) {  // near-active local maxima: probe around them
    const double v = value(i);
    if (v > -kProbeBand && v >= value(i - 1) && v >= value(i + 1))
      for (double f : {-0.75, -0.5, -0.25, 0.25, 0.5, 0.75})
        probes.push_back(node(i) + f * (f < 0.0 ? node(i) - node(i + 1) : node(i - 1) - node(i)));
  }
  for (int i = 0; i < points; ++i) {
    const double v = value(i);
    if (!(v > threshold)) continue;
    const bool left = i == 0 || value(i - 1) <= v, right = i == points - 1 || value(i + 1) < v;
    // Only the maxima: a point of a rising stretch next to a maximum would duplicate its row
    // (nearly dependent rows stall SLSQP; measured on Chesse).
    if (!left || !right) continue;
    const bool inside = i > 0 && i < points - 1;
    maxima.push_back(inside ? parabolaVertex(node(i - 1), value(i - 1), node(i), v, node(i + 1),
                                             value(i + 1))
                            : node(i));
  }
}

void sortUnique(std::vector<double>& s) {
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end(), [](double a, double b) { return b - a < 1e-9; }),
          s.end());
}

// Evaluates the step with the probe points as extra constraint points and folds their values
// into the check (the worst value between the refined nodes).
void probe(const GaitEvaluator& ev, const GaitParameters& p, const GaitOptions& o,
           BetweenNodesCheck& r) {
  if (o.ss_extra_points.empty() && o.ds_extra_points.empty()) return;
  const GaitEvaluator probed(ev.model().robot, o, ev.model().options);
  const GaitEvaluation<double> e = probed.evaluate(p);
  const ConstraintLayout& layout = probed.layout();
  for (const ConstraintGroup& g : layout.groups()) {
    if (g.phase == ConstraintPhase::None || g.count == 0) continue;
    const bool ss = g.phase == ConstraintPhase::SingleSupport;
    const std::vector<double>& points = ss ? o.ss_extra_points : o.ds_extra_points;
    const int first_extra = g.count / g.per_point - static_cast<int>(points.size());
    for (int j = 0; j < static_cast<int>(points.size()); ++j)
      for (int sub = 0; sub < g.per_point; ++sub) {
        const int k = g.offset + (first_extra + j) * g.per_point + sub;
        if (e.state[k] == ConstraintState::NotComputed) continue;
        const double scaled = e.g[k] / g.scale;
        const int id = layout.groupOf(k);
        r.group_worst_scaled[id] = std::max(r.group_worst_scaled[id], scaled);
        if (scaled > r.worst_scaled) {
          r.worst_scaled = scaled;
          r.worst_value = e.g[k];
          r.worst_group = id;
        }
      }
  }
}

}  // namespace

BetweenNodesCheck checkBetweenNodes(const GaitEvaluator& ev, const GaitParameters& p,
                                    double threshold) {
  GaitOptions o = ev.options();
  o.ss_nodes *= kBetweenNodesRefinement;
  o.ds_nodes *= kBetweenNodesRefinement;
  o.ss_extra_points.clear();
  o.ds_extra_points.clear();
  o.split_criteria_kinks = false;  // constraints only
  const GaitEvaluator fine(ev.model().robot, o, ev.model().options);
  const GaitEvaluation<double> e = fine.evaluate(p);
  BetweenNodesCheck r;
  r.ss_nodes = o.ss_nodes;
  r.ds_nodes = o.ds_nodes;
  r.computed = e.motion_computed;
  r.worst_scaled = kNone;
  const ConstraintLayout& layout = fine.layout();
  r.group_worst_scaled.assign(layout.groups().size(), kNone);
  for (int k = 0; k < layout.size(); ++k) {
    const int g = layout.groupOf(k);
    if (layout[g].phase == ConstraintPhase::None || e.state[k] == ConstraintState::NotComputed)
      continue;
    const double scaled = e.g[k] / layout[g].scale;
    r.group_worst_scaled[g] = std::max(r.group_worst_scaled[g], scaled);
    if (scaled > r.worst_scaled) {
      r.worst_scaled = scaled;
      r.worst_value = e.g[k];
      r.worst_group = g;
    }
  }
  GaitOptions probe_options = ev.options();
  probe_options.split_criteria_kinks = false;
  probe_options.ss_extra_points.clear();
  probe_options.ds_extra_points.clear();
  for (const ConstraintGroup& group : layout.groups()) {
    if (group.phase == ConstraintPhase::None) continue;
    const bool ss = group.phase == ConstraintPhase::SingleSupport;
    for (int sub = 0; sub < group.per_point; ++sub)
      scanSequence(fine, e, group, sub, threshold, ss ? r.ss_maxima : r.ds_maxima,
                   ss ? probe_options.ss_extra_points : probe_options.ds_extra_points);
  }
  sortUnique(probe_options.ss_extra_points);
  sortUnique(probe_options.ds_extra_points);
  if (r.computed) probe(ev, p, probe_options, r);
  sortUnique(r.ss_maxima);
  sortUnique(r.ds_maxima);
  return r;
}

FeasibilityVerdict feasibilityVerdict(const GaitEvaluator& ev, const GaitParameters& p,
                                      const GaitEvaluation<double>& e,
                                      std::optional<double> speed) {
  FeasibilityVerdict v;
  const ConstraintLayout& layout = ev.layout();
  std::vector<bool> unmet(layout.groups().size(), false);
  for (int k = 0; k < layout.size(); ++k) {
    if (e.state[k] == ConstraintState::NotComputed) continue;
    v.max_violation = std::max(v.max_violation, e.g[k]);
    if (layout.violates(k, e.g[k])) unmet[layout.groupOf(k)] = true;
  }
  if (e.motion_computed) {
    v.between_nodes = checkBetweenNodes(ev, p);
    for (std::size_t g = 0; g < unmet.size(); ++g)
      if (v.between_nodes.group_worst_scaled[g] > kFeasibilityTolerance) unmet[g] = true;
  }
  bool speed_unmet = false;
  if (speed && zeroDynamicsComputed(ev, e)) {
    v.speed_error = e.speed - *speed;
    v.max_violation = std::max(v.max_violation, std::abs(*v.speed_error));
    speed_unmet = !(std::abs(*v.speed_error) <= kFeasibilityTolerance);
  }
  for (std::size_t g = 0; g < unmet.size(); ++g)
    if (unmet[g] && (v.failed_level < 0 || layout[g].level < v.failed_level))
      v.failed_level = layout[g].level;
  if (v.failed_level < 0 && (speed_unmet || (speed && !v.speed_error))) v.failed_level = 5;
  // A motion that overflowed is reported as failed at level 4 by the evaluator.
  if (v.failed_level < 0 && !e.motion_computed)
    v.failed_level = e.failed_level < 0 ? 4 : e.failed_level;
  for (std::size_t g = 0; g < unmet.size(); ++g)
    if (unmet[g] && layout[g].level == v.failed_level) v.unmet_groups.push_back(layout[g].name);
  if (v.failed_level == 5 && speed_unmet) v.unmet_groups.push_back("speed");
  v.feasible = v.failed_level < 0;
  return v;
}

FeasibilityVerdict feasibilityVerdict(const GaitEvaluator& ev, const GaitParameters& p,
                                      const GaitEvaluation<double>& e) {
  const double target = ev.options().target_speed;
  return feasibilityVerdict(ev, p, e, target > 0.0 ? std::optional<double>(target) : std::nullopt);
}

}  // namespace gaitopt
