#pragma once
// Runs of one problem from several starts (`gaitopt optimize --random-starts K`, the optimised
// starts of --global): the runs from seeded random starts, the best of them and the spread of
// their optima.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <vector>

#include "gaitopt/opt/optimizer.hpp"

namespace gaitopt {

struct StartRun {
  int start = 0;  // 1-based index of the random start; 0 for the configured initial guess
  OptimizationResult result;
};

// The optimal runs: how many, and their lowest and highest criterion (empty when none).
struct StartsSummary {
  int converged = 0;
  std::optional<double> min, max;
};
StartsSummary summarizeStarts(const std::vector<StartRun>& runs, Criterion criterion);

// Index of the best run (result_order.hpp, levels met before violation; the earliest on ties).
std::size_t bestStartRun(const std::vector<StartRun>& runs, Criterion criterion);

// `count` runs, start k (1-based) drawn by randomStart around request.initial from one
// std::mt19937_64 seeded with `seed`. `after_run` is called after each run (progress).
std::vector<StartRun> optimizeFromRandomStarts(const GaitEvaluator& evaluator,
                                               const OptimizationRequest& request, int count,
                                               std::uint64_t seed, std::ostream* log,
                                               const std::function<void(const StartRun&)>& after_run);

}  // namespace gaitopt
