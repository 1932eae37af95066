#pragma once
// One feasibility verdict for a walking step, shared by `gaitopt evaluate`, summary.json and the
// optimiser's status: every computed constraint entry within kFeasibilityTolerance × its
// group's scale (gait/constraints.hpp), the speed within kFeasibilityTolerance m/s of its
// target, and the semi-infinite constraints (3.36)–(3.50) also between the grid nodes, checked
// on grids kBetweenNodesRefinement times finer.
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
};

// `speed`: the target speed, if any (the optimiser's request, or options.target_speed).
FeasibilityVerdict feasibilityVerdict(const GaitEvaluator& evaluator, const GaitParameters& p,
                                      const GaitEvaluation<double>& evaluation,
                                      std::optional<double> speed);
// The same with the speed target of the evaluator's options (none when target_speed is 0).
FeasibilityVerdict feasibilityVerdict(const GaitEvaluator& evaluator, const GaitParameters& p,
                                      const GaitEvaluation<double>& evaluation);

}  // namespace gaitopt
