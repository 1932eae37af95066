// `gaitopt optimize`: an optimal walking step from an optimiser configuration file →
// summary.json, gait.yaml and trajectory.csv; optionally from K seeded random starts.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/gait/constraint_summary.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/io/optimize_output.hpp"
#include "gaitopt/opt/global_search.hpp"
#include "gaitopt/opt/optimizer.hpp"
#include "gaitopt/opt/start_runs.hpp"
#include "override_options.hpp"

namespace gaitopt::cli {
namespace {

// Seeds are written to summary.json as JSON numbers, exact up to 2^53.
constexpr std::uint64_t kMaxSeed = (std::uint64_t{1} << 53) - 1;

struct OptimizeArgs {
  std::string config, out;
  OverrideArgs overrides;
  int random_starts = 0;  // 0: one run from the configured initial guess
  int global = 0;         // > 0: globalSearch with that many starts
  std::uint64_t seed = 1;
  bool quiet = false, verbose = false;
  std::string progress = "auto";
};

void printClusters(std::ostream& out, const GlobalSearchResult& g, Criterion c) {
  out << "global: " << g.converged << " of " << g.starts.size() - g.skipped
      << " optimised starts optimal (" << g.skipped << " skipped in known basins), "
      << g.clusters.size() << " clusters, median " << shortNumber(g.median_time_per_start_s, "%.3g")
      << " s per start\n";
  for (const OptimumCluster& cl : g.clusters)
    out << "  " << criterionName(c) << " " << shortNumber(cl.criterion, "%.6g") << ": "
        << cl.size() << " start(s)\n";
}

void printStartsTable(std::ostream& out, const std::vector<StartRun>& runs, Criterion c) {
  char line[128];
  std::snprintf(line, sizeof line, "%6s  %-10s  %14s  %10s  %9s  %s\n", "start", "status",
                criterionName(c), "iterations", "wall [s]", "unmet");
  out << line;
  for (const StartRun& run : runs) {
    std::string unmet = run.result.unmet_level < 0 ? "-" : std::to_string(run.result.unmet_level);
    for (std::size_t i = 0; i < run.result.unmet_constraints.size(); ++i) {
      unmet += (i == 0 ? ": " : ", ") + run.result.unmet_constraints[i];
    }
    std::snprintf(line, sizeof line, "%6d  %-10s  %14s  %10d  %9.3f  ", run.start,
                  optimizationStatusName(run.result.status), criterionText(run.result, c).c_str(),
                  run.result.iterations, run.result.wall_time_s);
    out << line << unmet << "\n";
  }
  const StartsSummary s = summarizeStarts(runs, c);
  out << "converged " << s.converged << "/" << runs.size();
  if (s.min) {
    out << ", " << criterionName(c) << " from " << shortNumber(*s.min) << " to "
        << shortNumber(*s.max) << " (spread " << shortNumber(*s.max - *s.min) << ")";
  }
  out << "\n";
}

}  // namespace

void registerOptimizeCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<OptimizeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "optimize",
      "Optimise one walking step as configured in an optimiser YAML file: writes "
      "OUT/summary.json, OUT/gait.yaml and, for a defined step, OUT/trajectory.csv (the best "
      "point found, also when it is infeasible). Exit 0: optimal; 3: infeasible, iteration "
      "limit or solver failure (outputs still written); 2: bad input (nothing written).");
  cmd->add_option("--config", args->config, "Optimiser configuration YAML file")->required();
  cmd->add_option("--out", args->out, "Output directory (created if missing)")->required();
  addOverrideOptions(cmd, args->overrides, "speed");
  CLI::Option* starts =
      cmd->add_option("--random-starts", args->random_starts,
                      "Optimise from K random starts in the documented box around the "
                      "configured initial guess, and keep the best")
          ->check(integerWithin(1, 100000));
  CLI::Option* global =
      cmd->add_option("--global", args->global,
                      "Multi-start global search: K random starts (the same box), starts inside "
                      "the basin of an optimum already found skipped, the local optima "
                      "clustered (0.1 %), the best one polished")
          ->check(integerWithin(1, 100000))
          ->excludes(starts);
  CLI::Option* seed =
      cmd->add_option("--seed", args->seed,
                      "Seed of the random starts of --random-starts or --global "
                      "(std::mt19937_64), 0 to 2^53-1; default 1")
          ->check(integerWithin(0, kMaxSeed));
  cmd->add_flag("--quiet", args->quiet, "No progress lines");
  cmd->add_flag("--verbose", args->verbose,
                "Also the solver's own lines (scaled objective and violation)");
  cmd->add_option("--progress", args->progress,
                  "auto: one line per stage (updated in place on a terminal); lines: every line")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "lines"}));
  cmd->callback([args, &exit_code, seed, starts, global]() {
    if (seed->count() > 0 && starts->count() == 0 && global->count() == 0)
      throw CLI::RequiresError("--seed", "--random-starts or --global");
    // Everything that can fail on bad input happens before the output directory is touched.
    OptimizeConfig config =
        loadOptimizeConfigWithOverrides(args->config, overridesOf(args->overrides, "speed"));
    OutputTransaction output({{"--config", args->config}});
    const std::string dir = output.directory("--out", args->out, ourOutputs(&config.solver));
    placeIpoptOutputFile(config.solver, dir);

    const GaitEvaluator evaluator(config.robot, config.options, config.model_options);
    const GaitParameters initial = configuredInitialGuess(config, evaluator.model());
    std::ostream* log = args->quiet ? nullptr : &std::cout;
    const Criterion criterion = config.criterion;
    // Progress in user units from the solver's hook; its own (scaled) lines with --verbose.
    OptimizeProgress progress_lines(
        evaluator, criterion, args->progress == "lines" ? ProgressMode::Lines : ProgressMode::Auto,
        std::cout);
    if (!args->quiet) config.solver.on_iteration = progress_lines.hook();
    if (!args->verbose) config.solver.print_every = 0;
    const auto start_time = std::chrono::steady_clock::now();

    std::vector<StartRun> runs;
    GlobalSearchResult global_result;
    const OptimizationRequest request = optimizationRequest(config, initial);
    if (args->global > 0) {
      global_result = globalSearch(evaluator, request,
                                   globalSearchSettings(args->global, args->seed), log);
      progress_lines.endLine();
      for (const GlobalStart& st : global_result.starts)
        if (!st.skipped) runs.push_back({st.index, st.result});
    } else if (args->random_starts == 0) {
      runs.push_back({0, optimizeGait(evaluator, request, log)});
      progress_lines.endLine();
    } else {
      runs = optimizeFromRandomStarts(
          evaluator, request, args->random_starts, args->seed, log, [&](const StartRun& run) {
            progress_lines.endLine();
            if (!log) return;
            const double elapsed =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time)
                    .count();
            *log << "--- random start " << run.start << "/" << args->random_starts << ": "
                 << run.result.status << ", "
                 << progressText(evaluator, run.result.evaluation, criterion) << ", "
                 << elapsedAndRemaining(elapsed, run.start, args->random_starts) << "\n";
          });
    }
    const std::size_t best = bestStartRun(runs, criterion);
    // --global reports its polished best, which is not one of the listed starts.
    const OptimizationResult& r = args->global > 0 ? global_result.best : runs[best].result;
    const GaitEvaluation<double>& e = r.evaluation;

    // summary.json (with criterion and solver), gait.yaml, trajectory.csv: io/optimize_output.hpp.
    const OptimizationOutputs outputs =
        optimizationOutputs(evaluator, config, r, args->out, [&](JsonWriter& w) {
          if (args->random_starts > 0)
            writeRandomStartsJson(w, runs, args->seed, runs[best].start, criterion);
          if (args->global > 0) writeGlobalSearchJson(w, global_result, runs, args->seed, criterion);
        });
    writeOptimizationOutputs(dir, outputs);
    output.commit();

    if (args->random_starts > 0) printStartsTable(std::cout, runs, criterion);
    if (args->global > 0) printClusters(std::cout, global_result, criterion);
    std::cout << "optimize: " << r.status << ", " << criterionName(criterion) << " "
              << criterionText(r, criterion) << " " << criterionUnit(criterion) << ", speed "
              << (zeroDynamicsComputed(evaluator, e) ? shortNumber(e.speed, "%.6g") + " m/s"
                                                     : std::string("n/a"))
              << ", " << r.iterations << " iterations, " << shortNumber(r.wall_time_s, "%.3g")
              << " s -> " << args->out << "\n";
    if (isOptimal(r)) {
      exit_code = 0;
      return;
    }
    std::ostringstream names;
    for (std::size_t i = 0; i < r.unmet_constraints.size(); ++i)
      names << (i == 0 ? "" : ", ") << r.unmet_constraints[i];
    std::cerr << "gaitopt: optimize: status " << r.status << "; unmet level "
              << (r.unmet_level < 0 ? std::string("none") : std::to_string(r.unmet_level))
              << (r.unmet_constraints.empty() ? std::string() : ": " + names.str())
              << "; largest violation " << shortNumber(r.constraint_violation, "%.4g")
              << "; the best point found was written to " << args->out << "\n";
    const std::string friction = robotFrictionMessage(evaluator.layout(), r.robot_friction);
    if (!friction.empty()) std::cerr << "gaitopt: optimize: " << friction << "\n";
    exit_code = kExitUndefined;
  });
}

}  // namespace gaitopt::cli
