#pragma once
// Multi-start global search (`gaitopt optimize --global K`): K seeded random starts
// (random_start.hpp), each optimised locally by optimizeGait; the local optima are grouped in
// clusters of equal criterion, and the best one is polished by a last run started from it.
// MLSL-style (Rinnooy Kan & Timmer): a start lying inside the basin of an optimum already found
// (closer to it than `basin_radius` in the scaled norm) is not optimised, it would only find
// that optimum again.
#include <cstdint>
#include <ostream>
#include <vector>

#include "gaitopt/opt/optimizer.hpp"
#include "gaitopt/opt/start_restarts.hpp"

namespace gaitopt {

// Local optima of (nearly) equal criterion. Values are taken in increasing order; a value joins
// the current cluster when it is within rel_tol (relative) of the cluster's lowest value,
// otherwise it opens a new cluster. Clusters are listed lowest criterion first.
struct OptimumCluster {
  double criterion = 0.0;    // lowest value of the cluster
  std::vector<int> members;  // indices into the clustered list, in increasing value
  int size() const { return static_cast<int>(members.size()); }
};
std::vector<OptimumCluster> clusterOptima(const std::vector<double>& values, double rel_tol);

struct GlobalSearchSettings {
  int starts = 20;
  std::uint64_t seed = 1;
  double cluster_tolerance = 1e-3;  // relative, 0.1 %
  // RMS over the parameters of (p − optimum)/parameterScales(); 0 disables the skip.
  double basin_radius = 0.1;
  // Each optimised start refined (start_restarts.hpp); max_restarts = max_retries = 0 for
  // the plain staged solve.
  RestartSettings restart_settings;
};

// The settings of `gaitopt optimize --global K --seed S` (the library defaults otherwise), shared
// with bench_optimize's `--global-per-start K` so that the bench measures what users run.
GlobalSearchSettings globalSearchSettings(int starts, std::uint64_t seed);

struct GlobalStart {
  int index = 0;  // 1-based
  GaitParameters start;
  bool skipped = false;  // inside the basin of an optimum found earlier: not optimised
  OptimizationResult result;  // empty when skipped; after the restarts
  int restarts = 0, retries = 0, perturbed_restarts = 0;  // of the restarts
};

struct GlobalSearchResult {
  std::vector<GlobalStart> starts;
  std::vector<OptimumCluster> clusters;  // over the optimal runs; members are start indices (1-based)
  OptimizationResult best;  // the polish run from the best local optimum (or the best run)
  int best_start = 0;       // 1-based; 0 when no run converged
  int converged = 0, skipped = 0;
  double median_time_per_start_s = 0.0;  // over the optimised (not skipped) starts
};

// Scaled RMS distance used for the basin test.
double scaledRmsDistance(const GaitParameters& a, const GaitParameters& b,
                         const Parameterisation& par);

// `request.initial` is the centre of the random-start box; its solver settings apply to every
// run. Same seed, same starts, same results (wall times apart): the restarts' perturbations
// come from a second generator, so the starts do not depend on the restart settings.
GlobalSearchResult globalSearch(const GaitEvaluator& evaluator, const OptimizationRequest& request,
                                const GlobalSearchSettings& settings, std::ostream* log = nullptr);

}  // namespace gaitopt
