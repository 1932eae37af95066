#pragma once
// One feasibility verdict for a walking step, shared by `gaitopt evaluate`, summary.json and the
// optimiser's status: every computed constraint entry within kFeasibilityTolerance × its
// group's scale (gait/constraints.hpp), the speed within kFeasibilityTolerance m/s of its
// target, and the semi-infinite constraints (3.36)–(3.50) also between the grid nodes, checked
// on grids kBetweenNodesRefinement times finer; without dry friction, the torque envelope also
// with the robot's whole friction (the torque the exported feedforward asks for).
#include <optional>
#include <string>
#include <vector>

#include "gaitopt/gait/evaluator.hpp"

namespace gaitopt {

constexpr int kBetweenNodesRefinement = 10;

// The phase-wise constraints of the same step evaluated with 10× the nodes.
struct BetweenNodesCheck {
  bool computed = false;           // the refined evaluation computed the motion
  int ss_nodes = 0, ds_nodes = 0;  // refined grids
  double worst_scaled = 0.0;       // max of g / scale over the refined phase-wise entries
  double worst_value = 0.0;        // that entry's g, in its group's unit
  int worst_group = -1;            // −1 when no phase-wise entry was computed
  std::vector<double> group_worst_scaled;  // per group (−∞ for non-phase-wise groups)
};

BetweenNodesCheck checkBetweenNodes(const GaitEvaluator& evaluator, const GaitParameters& p);
// The evaluator of that check: the same step with kBetweenNodesRefinement × the SS and DS
// nodes (Chebyshev–Lobatto grids, so its node 10 k is node k of `evaluator`), constraints only.
GaitEvaluator betweenNodesEvaluator(const GaitEvaluator& evaluator);

// A step evaluated without dry friction (GaitOptions::dry_friction false) bounds a Γ* without
// the robot's Coulomb friction, which the exported feedforward adds: its torque envelope rows
// (torque_envelope_ss, torque_envelope_ds) evaluated again with the robot's whole friction, at
// the nodes and on the 10× finer grids.
struct RobotFrictionCheck {
  bool checked = false;  // dry friction off, the robot has Coulomb friction, the motion computed
  int worst_group = -1;  // the torque group with the largest excess
  double excess = 0.0;   // its largest Γ* − Γmax [N·m] (≤ 0: within the envelope)
  bool met = true;       // excess within kFeasibilityTolerance × the group's scale
};

RobotFrictionCheck checkRobotFriction(const GaitEvaluator& evaluator, const GaitParameters& p);
// "torque_envelope_ss exceeds the torque envelope by 16.5 N m with the robot's Coulomb friction
// (dry_friction: false)"; empty when the check is met or was not made.
std::string robotFrictionMessage(const ConstraintLayout& layout, const RobotFrictionCheck& c);

struct FeasibilityVerdict {
  bool feasible = false;
  int failed_level = -1;  // lowest level with an unmet constraint (5 for the speed), −1: none
  std::vector<std::string> unmet_groups;  // groups of that level ("speed" for the speed)
  double max_violation = 0.0;  // largest g over computed node entries and |speed error|, ≥ 0
  // Largest scaled value over the node entries, the 10× finer check and |speed error| (m/s):
  // how far a step is from the verdict, comparable between steps of one problem.
  double worst_scaled = 0.0;
  std::optional<double> speed_error;
  BetweenNodesCheck between_nodes;  // computed only when the motion is
  RobotFrictionCheck robot_friction;  // an unmet check makes its group unmet at level 5
};

// `speed`: the target speed, if any (the optimiser's request, or options.target_speed).
FeasibilityVerdict feasibilityVerdict(const GaitEvaluator& evaluator, const GaitParameters& p,
                                      const GaitEvaluation<double>& evaluation,
                                      std::optional<double> speed);
// The same with the speed target of the evaluator's options (none when target_speed is 0).
FeasibilityVerdict feasibilityVerdict(const GaitEvaluator& evaluator, const GaitParameters& p,
                                      const GaitEvaluation<double>& evaluation);

}  // namespace gaitopt
