#include "gaitopt/gait/feasibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "gaitopt/gait/constraint_summary.hpp"

namespace gaitopt {

GaitEvaluator betweenNodesEvaluator(const GaitEvaluator& ev) {
  GaitOptions o = ev.options();
  o.ss_nodes *= kBetweenNodesRefinement;
  o.ds_nodes *= kBetweenNodesRefinement;
  o.criteria_refinement = 1;  // constraints only: W and C_E are not read
  return GaitEvaluator(ev.model().robot, o, ev.model().options);
}

BetweenNodesCheck checkBetweenNodes(const GaitEvaluator& ev, const GaitParameters& p) {
  const GaitEvaluator fine = betweenNodesEvaluator(ev);
  const GaitEvaluation<double> e = fine.evaluate(p);
  const ConstraintLayout& layout = fine.layout();
  BetweenNodesCheck r;
  r.ss_nodes = fine.options().ss_nodes;
  r.ds_nodes = fine.options().ds_nodes;
  r.computed = e.motion_computed;
  r.worst_scaled = -std::numeric_limits<double>::infinity();
  r.group_worst_scaled.assign(layout.groups().size(), r.worst_scaled);
  for (int id = 0; id < static_cast<int>(layout.groups().size()); ++id) {
    const ConstraintGroup& g = layout[id];
    if (g.phase == ConstraintPhase::None) continue;
    const double scale = constraintGroupScale(id, ev.model());
    for (int k = g.offset; k < g.offset + g.count; ++k) {
      if (e.state[k] == ConstraintState::NotComputed) continue;
      const double scaled = e.g[k] / scale;
      r.group_worst_scaled[id] = std::max(r.group_worst_scaled[id], scaled);
      if (scaled > r.worst_scaled) {
        r.worst_scaled = scaled;
        r.worst_value = e.g[k];
        r.worst_group = id;
      }
    }
  }
  return r;
}

RobotFrictionCheck checkRobotFriction(const GaitEvaluator& ev, const GaitParameters& p) {
  RobotFrictionCheck r;
  const RobotParams& robot = ev.model().robot;
  if (ev.options().dry_friction ||
      std::all_of(robot.coulomb.begin(), robot.coulomb.end(), [](double c) { return c == 0.0; }))
    return r;
  GaitOptions o = ev.options();
  o.dry_friction = true;
  o.criteria_refinement = 1;  // constraints only
  const GaitEvaluator full(robot, o, ev.model().options);
  const GaitEvaluation<double> e = full.evaluate(p);
  if (!e.motion_computed) return r;
  const BetweenNodesCheck fine = checkBetweenNodes(full, p);
  r.checked = true;
  r.excess = -std::numeric_limits<double>::infinity();
  for (int id : {kTorqueSS, kTorqueDS}) {
    const ConstraintGroup& g = full.layout()[id];
    const double scale = constraintGroupScale(id, full.model());
    double worst = fine.group_worst_scaled[id] * scale;
    for (int k = g.offset; k < g.offset + g.count; ++k)
      if (e.state[k] != ConstraintState::NotComputed) worst = std::max(worst, e.g[k]);
    if (worst > r.excess) {
      r.excess = worst;
      r.worst_group = id;
    }
  }
  r.met = r.excess <= kFeasibilityTolerance * constraintGroupScale(r.worst_group, full.model());
  return r;
}

std::string robotFrictionMessage(const ConstraintLayout& layout, const RobotFrictionCheck& c) {
  if (!c.checked || c.met) return "";
  char excess[32];
  std::snprintf(excess, sizeof excess, "%.4g", c.excess);
  return layout[c.worst_group].name + " exceeds the torque envelope by " + excess + " " +
         layout[c.worst_group].unit + " with the robot's Coulomb friction (dry_friction: false)";
}

FeasibilityVerdict feasibilityVerdict(const GaitEvaluator& ev, const GaitParameters& p,
                                      const GaitEvaluation<double>& e,
                                      std::optional<double> speed) {
  FeasibilityVerdict v;
  const ConstraintLayout& layout = ev.layout();
  std::vector<bool> unmet(layout.groups().size(), false);
  for (int id = 0; id < static_cast<int>(layout.groups().size()); ++id) {
    const ConstraintGroup& g = layout[id];
    const double scale = constraintGroupScale(id, ev.model());
    for (int k = g.offset; k < g.offset + g.count; ++k) {
      if (e.state[k] == ConstraintState::NotComputed) continue;
      v.max_violation = std::max(v.max_violation, e.g[k]);
      v.worst_scaled = std::max(v.worst_scaled, e.g[k] / scale);
      if (!(e.g[k] <= kFeasibilityTolerance * scale)) unmet[id] = true;
    }
  }
  if (e.motion_computed) {
    v.between_nodes = checkBetweenNodes(ev, p);
    v.worst_scaled = std::max(v.worst_scaled, v.between_nodes.worst_scaled);
    for (std::size_t g = 0; g < unmet.size(); ++g)
      if (v.between_nodes.group_worst_scaled[g] > kFeasibilityTolerance) unmet[g] = true;
    v.robot_friction = checkRobotFriction(ev, p);
    if (v.robot_friction.checked) {
      const int g = v.robot_friction.worst_group;
      v.max_violation = std::max(v.max_violation, v.robot_friction.excess);
      v.worst_scaled =
          std::max(v.worst_scaled, v.robot_friction.excess / constraintGroupScale(g, ev.model()));
      if (!v.robot_friction.met) unmet[g] = true;
    }
  }
  bool speed_unmet = false;
  if (speed && zeroDynamicsComputed(ev, e)) {
    v.speed_error = e.speed - *speed;
    v.max_violation = std::max(v.max_violation, std::abs(*v.speed_error));
    v.worst_scaled = std::max(v.worst_scaled, std::abs(*v.speed_error));
    speed_unmet = !(std::abs(*v.speed_error) <= kFeasibilityTolerance);
  }
  for (std::size_t g = 0; g < unmet.size(); ++g)
    if (unmet[g] && (v.failed_level < 0 || layout[g].level < v.failed_level))
      v.failed_level = layout[g].level;
  if (v.failed_level < 0 && (speed_unmet || (speed && !v.speed_error))) v.failed_level = 5;
  // Levels 0–4 within the tolerance but failed strictly (g in (0, tol]): the evaluator still
  // stopped there, so the motion is missing and the step cannot be feasible.
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
