#pragma once
// The outputs of one optimised walking step, shared by `gaitopt optimize` and `gaitopt sweep`:
// summary.json (the gait summary of io/summary_file.hpp plus `criterion` and `solver`, then any
// caller-specific members), gait.yaml (readable by `gaitopt evaluate` and as an initial guess)
// and trajectory.csv (only for a defined step whose motion was computed).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/opt/global_search.hpp"
#include "gaitopt/opt/optimizer.hpp"
#include "gaitopt/opt/start_runs.hpp"
#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/io/optimize_config.hpp"

namespace gaitopt {

struct OptimizationOutputs {
  std::string summary_json;
  std::string gait_yaml;
  std::optional<std::string> trajectory_csv;  // empty when the step has no computed motion
};

// The `solver` member: backend, hierarchy, status, iteration and evaluation counts, wall time,
// violation, unmet level and constraints, stages.
void writeSolverJson(JsonWriter& w, const SolverSettings& settings, const OptimizationResult& r);

// The robot file as seen from directory `dir` (relative when possible), so that a gait file
// written in `dir` finds it.
std::string robotPathFrom(const std::string& dir, const std::string& robot_path);

// The three documents for `result`, to be written into `dir`. `evaluator` must have been built
// from config.robot, config.options and config.model_options (its options give the summary's
// target_speed); `extra`, when given, adds members to summary.json after `solver`.
OptimizationOutputs optimizationOutputs(const GaitEvaluator& evaluator,
                                        const OptimizeConfig& config,
                                        const OptimizationResult& result, const std::string& dir,
                                        const std::function<void(JsonWriter&)>& extra = {});

// Creates `dir` if needed and writes the documents as new files; `dir` is a staging folder of
// an OutputTransaction (or a folder inside one), so that the three files appear together when
// it is published.
void writeOptimizationOutputs(const std::string& dir, const OptimizationOutputs& outputs);

// The `random_starts` member of summary.json (`gaitopt optimize --random-starts`): the count,
// seed, converged runs, criterion range and spread, the best start and every run.
void writeRandomStartsJson(JsonWriter& w, const std::vector<StartRun>& runs, std::uint64_t seed,
                           int best_start, Criterion criterion);

// The `global` member (`--global`): the clusters of local optima (criterion, size, starts), the
// median time per optimised start and every optimised run.
void writeGlobalSearchJson(JsonWriter& w, const GlobalSearchResult& g,
                           const std::vector<StartRun>& runs, std::uint64_t seed,
                           Criterion criterion);

}  // namespace gaitopt
