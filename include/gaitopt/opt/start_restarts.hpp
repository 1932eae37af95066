#pragma once
// Restarts and retries of one start of a multi-start search (global_search.hpp), measured on the random
// starts of the three shipped configurations (docs/commands/optimize.md):
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
// - perturbed restarts of an optimum that a plain restart no longer lowers: SLSQP started at
//   the same point retraces the same path and stops at the same non-KKT point (measured on
//   Chessé start 3 of seed 1: C_Γ 4454.1, active-set KKT residual 0.26–0.71), while started
//   nearby it reaches the best cluster (4004.4). The staged solve from points drawn within
//   `optimum_perturbation` × the half-widths around the optimum, kept when optimal and lower
//   by more than `min_improvement`.
#include <cstdint>
#include <ostream>
#include <random>

#include "gaitopt/opt/optimizer.hpp"

namespace gaitopt {

struct RestartSettings {
  int max_restarts = 4;
  double min_improvement = 1e-4;  // relative
  int max_retries = 3;
  double perturbation = 0.2;  // fraction of randomStartHalfWidths
  int max_perturbed_restarts = 3;
  double optimum_perturbation = 0.1;  // fraction of randomStartHalfWidths
};

struct RestartedStart {
  OptimizationResult result;  // wall time, iterations and evaluations summed over every solve
  int restarts = 0;           // restarts from an optimum that were run
  int retries = 0;            // perturbed retries of a start that was not optimal
  int perturbed_restarts = 0;  // perturbed restarts of an optimum that were run
};

// `first` is the staged solve of `request` (request.initial its start); the perturbations are
// drawn from `rng` only when a retry or a perturbed restart runs.
RestartedStart improveByRestarts(const GaitEvaluator& evaluator, const OptimizationRequest& request,
                            OptimizationResult first, const RestartSettings& settings,
                            std::mt19937_64& rng, std::ostream* log = nullptr);

}  // namespace gaitopt
