// `gaitopt optimize`: an optimal walking step from an optimiser configuration file →
// summary.json, gait.yaml and trajectory.csv; optionally from K seeded random starts.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/io/atomic_file.hpp"
#include "gaitopt/opt/global_search.hpp"
#include "gaitopt/opt/optimizer.hpp"
#include "gaitopt/gait/summary.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/io/optimize_output.hpp"
#include "gaitopt/opt/random_start.hpp"

namespace gaitopt::cli {
namespace {

// Seeds are written to summary.json as JSON numbers, exact up to 2^53.
constexpr std::uint64_t kMaxSeed = (std::uint64_t{1} << 53) - 1;

struct OptimizeArgs {
  std::string config;
  std::string out;
  int random_starts = 0;  // 0: one run from the configured initial guess
  int global = 0;         // > 0: globalSearch with that many starts
  std::uint64_t seed = 1;
  bool quiet = false, verbose = false;
  std::string progress = "auto";
};

struct Run {
  int start = 0;  // 1-based index of the random start; 0 for the configured initial guess
  OptimizationResult result;
};

bool isOptimal(const OptimizationResult& r) { return r.status == "optimal"; }

// How far a run got: every level met (6) above an unmet level 5, 4, ..., 0.
int progress(const OptimizationResult& r) { return r.unmet_level < 0 ? 6 : r.unmet_level; }

// Whether run a is better than run b: an optimal run with the lower criterion beats any other;
// among non-optimal runs, the one that got higher in the hierarchy, then the smaller
// violation. Ties keep the earlier run.
bool better(const OptimizationResult& a, const OptimizationResult& b, Criterion c) {
  if (isOptimal(a) != isOptimal(b)) return isOptimal(a);
  if (isOptimal(a)) return *criterionOf(a, c) < *criterionOf(b, c);
  if (progress(a) != progress(b)) return progress(a) > progress(b);
  return a.constraint_violation < b.constraint_violation;
}

void numberOrNull(JsonWriter& w, const std::optional<double>& v) {
  if (v) {
    w.value(*v);
  } else {
    w.null();
  }
}

struct StartsSummary {
  int converged = 0;
  std::optional<double> min, max;
};

StartsSummary summarizeStarts(const std::vector<Run>& runs, Criterion c) {
  StartsSummary s;
  for (const Run& run : runs) {
    if (!isOptimal(run.result)) continue;
    ++s.converged;
    const double v = *criterionOf(run.result, c);
    s.min = s.min ? std::min(*s.min, v) : v;
    s.max = s.max ? std::max(*s.max, v) : v;
  }
  return s;
}

void writeRuns(JsonWriter& w, const std::vector<Run>& runs, Criterion c) {
  w.key("runs").beginArray();
  for (const Run& run : runs) {
    w.beginObject();
    w.key("start").value(run.start);
    w.key("status").value(run.result.status);
    w.key("criterion");
    numberOrNull(w, criterionOf(run.result, c));
    w.key("iterations").value(run.result.iterations);
    w.key("wall_time_s").value(run.result.wall_time_s);
    w.key("unmet_level");
    if (run.result.unmet_level < 0) {
      w.null();
    } else {
      w.value(run.result.unmet_level);
    }
    w.endObject();
  }
  w.endArray();
}

void writeRandomStarts(JsonWriter& w, const std::vector<Run>& runs, std::uint64_t seed,
                       int best_start, Criterion c) {
  const StartsSummary s = summarizeStarts(runs, c);
  w.key("random_starts").beginObject();
  w.key("count").value(static_cast<int>(runs.size()));
  w.key("seed").value(static_cast<double>(seed));
  w.key("converged").value(s.converged);
  w.key("criterion_min");
  numberOrNull(w, s.min);
  w.key("criterion_max");
  numberOrNull(w, s.max);
  w.key("spread");
  numberOrNull(w, s.min ? std::optional<double>(*s.max - *s.min) : std::nullopt);
  w.key("best_start").value(best_start);
  writeRuns(w, runs, c);
  w.endObject();
}

// `global` in summary.json: the clusters of local optima (criterion, size, starts), the median
// time per optimised start and every optimised run.
void writeGlobal(JsonWriter& w, const GlobalSearchResult& g, const std::vector<Run>& runs,
                 std::uint64_t seed, Criterion c) {
  w.key("global").beginObject();
  w.key("count").value(static_cast<int>(g.starts.size()));
  w.key("seed").value(static_cast<double>(seed));
  w.key("optimised").value(static_cast<int>(runs.size()));
  w.key("skipped").value(g.skipped);
  w.key("converged").value(g.converged);
  w.key("median_time_per_start_s").value(g.median_time_per_start_s);
  w.key("best_start").value(g.best_start);
  w.key("clusters").beginArray();
  for (const OptimumCluster& cl : g.clusters) {
    w.beginObject();
    w.key("criterion").value(cl.criterion);
    w.key("size").value(cl.size());
    w.key("starts").beginArray();
    for (int m : cl.members) w.value(m);
    w.endArray();
    w.endObject();
  }
  w.endArray();
  writeRuns(w, runs, c);
  w.endObject();
}

void printClusters(std::ostream& out, const GlobalSearchResult& g, Criterion c) {
  out << "global: " << g.converged << " of " << g.starts.size() - g.skipped
      << " optimised starts optimal (" << g.skipped << " skipped in known basins), "
      << g.clusters.size() << " clusters, median " << shortNumber(g.median_time_per_start_s, "%.3g")
      << " s per start\n";
  for (const OptimumCluster& cl : g.clusters)
    out << "  " << criterionName(c) << " " << shortNumber(cl.criterion, "%.6g") << ": "
        << cl.size() << " start(s)\n";
}

void printStartsTable(std::ostream& out, const std::vector<Run>& runs, Criterion c) {
  char line[128];
  std::snprintf(line, sizeof line, "%6s  %-10s  %14s  %10s  %9s  %s\n", "start", "status",
                criterionName(c), "iterations", "wall [s]", "unmet");
  out << line;
  for (const Run& run : runs) {
    std::string unmet = run.result.unmet_level < 0 ? "-" : std::to_string(run.result.unmet_level);
    for (std::size_t i = 0; i < run.result.unmet_constraints.size(); ++i) {
      unmet += (i == 0 ? ": " : ", ") + run.result.unmet_constraints[i];
    }
    std::snprintf(line, sizeof line, "%6d  %-10s  %14s  %10d  %9.3f  ", run.start,
                  run.result.status.c_str(), criterionText(run.result, c).c_str(),
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
  CLI::Option* starts =
      cmd->add_option("--random-starts", args->random_starts,
                      "Optimise from K random starts in the box of the README around the "
                      "configured initial guess, and keep the best")
          ->check(CLI::Range(1, 100000));
  CLI::Option* global =
      cmd->add_option("--global", args->global,
                      "Multi-start global search: K random starts (the same box), starts inside "
                      "the basin of an optimum already found skipped, the local optima "
                      "clustered (0.1 %), the best one polished")
          ->check(CLI::Range(1, 100000))
          ->excludes(starts);
  CLI::Option* seed =
      cmd->add_option("--seed", args->seed,
                      "Seed of the random starts of --random-starts or --global "
                      "(std::mt19937_64), 0 to 2^53-1; default 1")
          ->check(CLI::Range(std::uint64_t{0}, kMaxSeed));
  cmd->add_flag("--quiet", args->quiet, "No progress lines");
  cmd->add_flag("--verbose", args->verbose,
                "Also the solver's own lines (scaled objective and violation)");
  cmd->add_option("--progress", args->progress,
                  "auto: on a terminal one line per stage updated in place; lines: every line")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "lines"}));
  cmd->callback([args, &exit_code, seed, starts, global]() {
    if (seed->count() > 0 && starts->count() == 0 && global->count() == 0)
      throw CLI::RequiresError("--seed", "--random-starts or --global");
    // Everything that can fail on bad input happens before the output directory is touched.
    OptimizeConfig config = loadOptimizeConfig(args->config);
    StagedDirectory staged(args->out, ourOutputs(&config.solver));  // --out checked before work
    placeIpoptOutputFile(config.solver, staged.path());

    const GaitEvaluator evaluator(config.robot, config.options, config.model_options);
    const GaitParameters initial = configuredInitialGuess(config, evaluator.model());
    std::ostream* log = args->quiet ? nullptr : &std::cout;
    const Criterion criterion = config.criterion;
    // Progress in user units from the solver's iteration hook; the solver's own (scaled) lines
    // only with --verbose.
    OptimizeProgress progress_lines(
        evaluator, criterion, args->progress == "lines" ? ProgressMode::Lines : ProgressMode::Auto,
        std::cout);
    if (!args->quiet) config.solver.on_iteration = progress_lines.hook();
    if (!args->verbose) config.solver.print_every = 0;
    const auto start_time = std::chrono::steady_clock::now();

    std::vector<Run> runs;
    GlobalSearchResult global_result;
    if (args->global > 0) {
      global_result = globalSearch(evaluator, optimizationRequest(config, initial),
                                   globalSearchSettings(args->global, args->seed), log);
      progress_lines.endLine();
      for (const GlobalStart& st : global_result.starts)
        if (!st.skipped) runs.push_back({st.index, st.result});
    } else if (args->random_starts == 0) {
      runs.push_back({0, optimizeGait(evaluator, optimizationRequest(config, initial), log)});
      progress_lines.endLine();
    } else {
      std::mt19937_64 rng(args->seed);
      for (int k = 1; k <= args->random_starts; ++k) {
        const GaitParameters start = randomStart(initial, rng, config.options.parameterisation);
        if (log) *log << "--- random start " << k << "/" << args->random_starts << "\n";
        runs.push_back({k, optimizeGait(evaluator, optimizationRequest(config, start), log)});
        progress_lines.endLine();
        if (log) {
          const double elapsed =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
          *log << "--- random start " << k << "/" << args->random_starts << ": "
               << runs.back().result.status << ", "
               << progressText(evaluator, runs.back().result.evaluation, criterion) << ", "
               << elapsedAndRemaining(elapsed, k, args->random_starts) << "\n";
        }
      }
    }
    std::size_t best = 0;
    for (std::size_t i = 1; i < runs.size(); ++i) {
      if (better(runs[i].result, runs[best].result, criterion)) best = i;
    }
    // --global reports its polished best, which is not one of the listed starts.
    const OptimizationResult& r = args->global > 0 ? global_result.best : runs[best].result;
    const GaitEvaluation<double>& e = r.evaluation;

    // summary.json (with criterion and solver), gait.yaml, trajectory.csv: io/optimize_output.hpp.
    const OptimizationOutputs outputs =
        optimizationOutputs(evaluator, config, r, args->out, [&](JsonWriter& w) {
          if (args->random_starts > 0) {
            writeRandomStarts(w, runs, args->seed, runs[best].start, criterion);
          }
          if (args->global > 0) writeGlobal(w, global_result, runs, args->seed, criterion);
        });
    writeOptimizationOutputs(staged.path(), outputs);
    staged.commit();

    if (args->random_starts > 0) printStartsTable(std::cout, runs, criterion);
    if (args->global > 0) printClusters(std::cout, global_result, criterion);
    std::cout << "optimize: " << r.status << ", " << criterionName(criterion) << " "
              << criterionText(r, criterion) << ", speed "
              << (zeroDynamicsComputed(evaluator, e) ? shortNumber(e.speed, "%.6g") + " m/s"
                                                     : std::string("n/a"))
              << ", " << r.iterations << " iterations, " << shortNumber(r.wall_time_s, "%.3g")
              << " s -> " << args->out << "\n";
    if (isOptimal(r)) {
      exit_code = 0;
      return;
    }
    std::ostringstream names;
    for (std::size_t i = 0; i < r.unmet_constraints.size(); ++i) {
      names << (i == 0 ? "" : ", ") << r.unmet_constraints[i];
    }
    std::cerr << "gaitopt: optimize: status " << r.status << "; unmet level "
              << (r.unmet_level < 0 ? std::string("none") : std::to_string(r.unmet_level))
              << (r.unmet_constraints.empty() ? std::string() : ": " + names.str())
              << "; largest violation " << shortNumber(r.constraint_violation, "%.4g")
              << "; the best point found was written to " << args->out << "\n";
    exit_code = kExitUndefined;
  });
}

}  // namespace gaitopt::cli
