#pragma once
// Refinement of one start of a multi-start search (global_search.hpp), measured on the random
// starts of the three shipped configurations (README "Start refinement"):
// - restarts from an optimum: SLSQP's stopping test (relative change of x and f below `tol`)
//   fires on a short step of a quasi-Newton model built across the kinks of the grid
//   constraints, far from a KKT point (measured: active-set KKT residual up to 0.6, criteria
//   40 % above the optimum found from the same point by one more solve). The whole staged
//   solve is run again from the point while it lowers the criterion by more than
//   `min_improvement` (relative): each restart rebuilds the model.
// - retries of a start that does not end optimal (mostly 1e-4…1e-2 outside level 5 at a
//   point where the active-set Newton closing and the restoration both fail): the staged solve
//   from points drawn uniformly within `perturbation` × the random-start half-widths
//   (random_start.hpp) around its last point, the first optimal result kept.
#include <cstdint>
#include <ostream>
#include <random>

#include "gaitopt/opt/optimizer.hpp"

namespace gaitopt {

struct StartRefinementSettings {
  int max_restarts = 4;
  double min_improvement = 1e-4;  // relative
  int max_retries = 3;
  double perturbation = 0.2;  // fraction of randomStartHalfWidths
};

struct StartRefinement {
  OptimizationResult result;  // wall time, iterations and evaluations summed over every solve
  int restarts = 0;           // restarts from an optimum that were run
  int retries = 0;            // perturbed retries of a start that was not optimal
};

// `first` is the staged solve of `request` (request.initial its start); the perturbations are
// drawn from `rng` only when a retry runs, so a start that converges uses no draw.
StartRefinement refineStart(const GaitEvaluator& evaluator, const OptimizationRequest& request,
                            OptimizationResult first, const StartRefinementSettings& settings,
                            std::mt19937_64& rng, std::ostream* log = nullptr);

}  // namespace gaitopt
