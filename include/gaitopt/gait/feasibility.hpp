#pragma once
// One feasibility verdict for a walking step, shared by `gaitopt evaluate`, summary.json and the
// optimiser's status: every computed constraint entry within kFeasibilityTolerance (scaled by
// its group's typical magnitude), the speed within kFeasibilityTolerance m/s of its target, and
// the semi-infinite constraints (3.36)–(3.50) also between the grid nodes, checked on a grid
// kBetweenNodesRefinement times finer.
#include <optional>
#include <string>
#include <vector>

#include "gaitopt/gait/evaluator.hpp"

namespace gaitopt {

constexpr int kBetweenNodesRefinement = 10;

// Phase-wise constraints on the refined grid (the same step evaluated with 10× the nodes),
// with a local refinement around its near-active local maxima (six more points between the
// refined nodes next to each).
struct BetweenNodesCheck {
  bool computed = false;           // the refined evaluation computed the motion
  int ss_nodes = 0, ds_nodes = 0;  // refined grids
  double worst_scaled = 0.0;       // max over phase-wise entries of g / scale (−∞ if none),
                                   // refined grid and local refinement
  double worst_value = 0.0;        // that entry's g, in its group's unit
  int worst_group = -1;
  std::vector<double> group_worst_scaled;  // per constraint group (−∞ for non-phase-wise)
  // Local maxima in s (Chebyshev coordinate of the phase, refined by a parabola through the
  // three points around each) of the entries whose scaled value exceeds the threshold asked.
  std::vector<double> ss_maxima, ds_maxima;
};

BetweenNodesCheck checkBetweenNodes(const GaitEvaluator& evaluator, const GaitParameters& p,
                                    double maxima_threshold = kFeasibilityTolerance);

struct FeasibilityVerdict {
  bool feasible = false;
  int failed_level = -1;  // lowest level with an unmet constraint (5 for the speed), −1: none
  std::vector<std::string> unmet_groups;  // groups of that level ("speed" for the speed)
  double max_violation = 0.0;  // largest g over computed node entries, and |speed error|; ≥ 0
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
