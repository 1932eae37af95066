// bench_optimize: wall-clock cost of whole optimisations on the shipped configurations.
//
//   bench_optimize [--json FILE] [--runs N] [--sweep-runs N] [--fd-runs N] [--no-ipopt]
//                  [--ipopt-runs N] [--ipopt-only] [--no-configs] [--help]
//   bench_optimize --random-starts N [--global-per-start K] [--start-config NAME]... [--json FILE]
//
// Measurements (configs/default.yaml, read with loadOptimizeConfig; the evaluator is built from
// the configuration exactly as `gaitopt optimize` builds it):
//   (a) optimizeGait from the configured start (defaultInitialGuess at the configured speed):
//       one untimed warm-up run, then `runs` timed runs (default 7); median, min, p90 of the
//       wall time. Every run must end with the same status and bit-identical C_Gamma.
//   (b) sweepSpeeds over 0.2:1.0:0.1 (9 speeds), jobs = 1, built as `gaitopt sweep` builds it
//       (free-speed evaluator, configured start without a speed): `sweep-runs` runs (default
//       3), median of the total wall time, number of optimal speeds; every run must give the
//       same statuses and C_Gamma.
//   (c) peak resident set size of the process after the sweeps (getrusage ru_maxrss) [MiB].
//   (d) Ipopt vs SLSQP side by side on configs/default.yaml, chesse_0.85.yaml and
//       chevallereau_aoustin_0.75.yaml (the last two unless --no-configs): each configuration
//       as shipped (SLSQP) and with backend Ipopt at the library's Ipopt defaults (dense BFGS
//       Hessian, every grid entry in one NLP, no polish), `ipopt-runs` runs each (default 3):
//       status, iterations, evaluations, wall-time median, final criterion, ratio Ipopt/SLSQP.
//       --ipopt-only runs (d) alone.
//   (g) --random-starts N: the random-start protocol alone: on the three
//       shipped configurations, N seeded starts (seed 1, the box of `--random-starts`, every
//       start optimised: globalSearch without the basin skip): converged rate, number of
//       clusters of optimal criteria (0.1 %), largest cluster's share of the N starts, median
//       wall time per start, best polished criterion; before them, one line per start (status,
//       unmet level and groups, violation, criterion, time) and its stages.
//       --start-config NAME (repeatable) restricts (g) to configs/NAME; --no-restarts and
//       --no-retries and --no-perturbed-restarts switch off the three levers of the start
//       restarts (start_restarts.hpp). --global-per-start K: each of the N "starts" is
//       instead run s = 1..N of `gaitopt optimize --global K --seed s` (globalSearchSettings,
//       the CLI's settings: basin skip on, every start refined, the best polished); its final
//       is the polished best, its time the run's wall time; the N finals are clustered (0.1 %)
//       and the line gives optimal runs, clusters, the best (lowest) cluster's share, median
//       wall time per run and the mean number of starts optimised (K minus the basin skips).
//   (e) the optimisation of (a) with GradientMode::FiniteDifference (SLSQP): median of
//       `fd-runs` (default 3); ratio to the exact-gradient median.
//   (f) exact vs finite-difference gradients on configs/default.yaml, chesse_0.85.yaml and
//       chevallereau_aoustin_0.75.yaml (the library call; optimiser configuration files have no
//       gradient key): status, iterations, function and gradient evaluations, wall time
//       (median of `fd-runs` for the two extra configurations), final criterion.
// Targets printed next to the figures: optimisation (a) median ≤ 0.2 s, 9-speed sweep (b)
// median ≤ 3 s. Exit status: 0, or 1 when a repeated measurement was not deterministic (or the
// JSON file cannot be written), 2 for bad arguments or unreadable configurations.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/opt/global_search.hpp"
#include "gaitopt/opt/optimizer.hpp"
#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/io/sweep_file.hpp"
#include "gaitopt/opt/result_order.hpp"

namespace {

using namespace gaitopt;
using namespace gaitopt::bench;

constexpr const char* kConfigDir = GAITOPT_SOURCE_DIR "/configs/";
constexpr const char* kSweepSpeeds = "0.2:1.0:0.1";
constexpr double kOptimizeTargetS = 0.2;
constexpr double kSweepTargetS = 3.0;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}


// One optimisation: its external wall time and the solver's figures.
struct Run {
  double wall_s = 0.0;
  std::string status;
  std::optional<double> criterion;
  int iterations = 0, function_evaluations = 0, gradient_evaluations = 0;
};

Run runOnce(const GaitEvaluator& ev, const OptimizationRequest& req, Criterion c) {
  const Clock::time_point t0 = Clock::now();
  const OptimizationResult r = optimizeGait(ev, req);
  Run run;
  run.wall_s = secondsSince(t0);
  run.status = optimizationStatusName(r.status);
  run.criterion = resultCriterion(r, c);
  run.iterations = r.iterations;
  run.function_evaluations = r.function_evaluations;
  run.gradient_evaluations = r.gradient_evaluations;
  g_sink = g_sink + (run.criterion ? *run.criterion : 0.0);
  return run;
}

// Identical status, criterion (bitwise) and counts.
bool sameOutcome(const Run& a, const Run& b) {
  return a.status == b.status && a.criterion.has_value() == b.criterion.has_value() &&
         (!a.criterion || *a.criterion == *b.criterion) && a.iterations == b.iterations &&
         a.function_evaluations == b.function_evaluations &&
         a.gradient_evaluations == b.gradient_evaluations;
}

struct Series {
  std::vector<Run> runs;
  SampleStats time;
  bool deterministic = true;
};

Series repeat(const GaitEvaluator& ev, const OptimizationRequest& req, Criterion c, int n) {
  Series s;
  std::vector<double> times;
  for (int i = 0; i < n; ++i) {
    s.runs.push_back(runOnce(ev, req, c));
    times.push_back(s.runs.back().wall_s);
    if (!sameOutcome(s.runs.back(), s.runs.front())) s.deterministic = false;
  }
  s.time = sampleStats(times);
  return s;
}

std::string criterionText(const std::optional<double>& v) {
  if (!v) return "n/a";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", *v);
  return buf;
}

// One configuration of the gradient comparison (f).

struct SweepRun {
  double wall_s = 0.0;
  int optimal = 0;
  std::vector<double> speeds;
  std::vector<std::string> status;
  std::vector<std::optional<double>> criterion;
  std::vector<int> attempts;
};

void usage(std::ostream& out) {
  out << "usage: bench_optimize [--json FILE] [--runs N] [--sweep-runs N] [--fd-runs N]\n"
         "                      [--no-ipopt] [--ipopt-runs N] [--ipopt-only] [--no-configs]\n"
         "                      [--random-starts N [--start-config NAME]... [--no-restarts]\n"
         "                       [--no-retries] [--no-perturbed-restarts]\n"
         "                       [--global-per-start K]]\n"
         "  --json FILE     also write every figure as JSON to FILE\n"
         "  --runs N        timed SLSQP optimisations of configs/default.yaml (default 7, >= 7)\n"
         "  --sweep-runs N  timed 9-speed sweeps (default 3)\n"
         "  --fd-runs N     finite-difference runs (and exact runs of the extra configs; default 3)\n"
         "  --no-ipopt      skip the Ipopt vs SLSQP comparison (d)\n"
         "  --ipopt-runs N  runs per solver and configuration in (d) (default 3)\n"
         "  --ipopt-only    run (d) alone\n"
         "  --no-configs    skip the chesse / chevallereau_aoustin gradient comparison\n"
         "  --random-starts N  run (g) alone: N seeded random starts on each shipped config\n"
         "  --start-config NAME  (g) on configs/NAME only (repeatable)\n"
         "  --no-restarts   (g) without the restarts from an optimum (start_restarts.hpp)\n"
         "  --no-retries    (g) without the perturbed retries of a start not optimal\n"
         "  --no-perturbed-restarts  (g) without the perturbed restarts near an optimum\n"
         "  --global-per-start K  (g) with N runs of `gaitopt optimize --global K --seed s`,\n"
         "                  s = 1..N, instead of N single starts\n";
}

// A number that may be absent (an undefined criterion): null in the JSON.
void writeNumberOrNull(JsonWriter& w, const char* key, const std::optional<double>& v) {
  w.key(key);
  if (v) w.value(*v);
  else w.null();
}

// The clusters of local optima (lowest first): criterion and size.
void writeClusters(JsonWriter& w, const std::vector<OptimumCluster>& clusters) {
  w.key("clusters").beginArray();
  for (const OptimumCluster& cl : clusters) {
    w.beginObject();
    w.key("criterion").value(cl.criterion);
    w.key("size").value(cl.size());
    w.endObject();
  }
  w.endArray();
}

void writeRun(JsonWriter& w, const Run& r) {
  w.beginObject();
  w.key("wall_time_s").value(r.wall_s);
  w.key("status").value(r.status);
  writeNumberOrNull(w, "criterion", r.criterion);
  w.key("iterations").value(r.iterations);
  w.key("function_evaluations").value(r.function_evaluations);
  w.key("gradient_evaluations").value(r.gradient_evaluations);
  w.endObject();
}

void writeSeries(JsonWriter& w, const Series& s) {
  w.beginObject();
  w.key("count").value(static_cast<int>(s.runs.size()));
  w.key("median_s").value(s.time.median);
  w.key("min_s").value(s.time.min);
  w.key("p90_s").value(s.time.p90);
  w.key("max_s").value(s.time.max);
  w.key("deterministic").value(s.deterministic);
  w.key("status").value(s.runs.front().status);
  writeNumberOrNull(w, "criterion", s.runs.front().criterion);
  w.key("iterations").value(s.runs.front().iterations);
  w.key("function_evaluations").value(s.runs.front().function_evaluations);
  w.key("gradient_evaluations").value(s.runs.front().gradient_evaluations);
  w.key("runs").beginArray();
  for (const Run& r : s.runs) writeRun(w, r);
  w.endArray();
  w.endObject();
}

void printSeriesRuns(const char* label, const Series& s) {
  for (std::size_t i = 0; i < s.runs.size(); ++i)
    std::printf("  %s run %zu: %8.3f s  status %-10s  C_Gamma %s  (%d iterations, %d f-evals, %d "
                "g-evals)\n",
                label, i + 1, s.runs[i].wall_s, s.runs[i].status.c_str(),
                criterionText(s.runs[i].criterion).c_str(), s.runs[i].iterations,
                s.runs[i].function_evaluations, s.runs[i].gradient_evaluations);
  std::printf("  %s: %s\n", label,
              s.deterministic ? "deterministic (same status, C_Gamma bit-identical, same counts)"
                              : "NON-DETERMINISTIC: runs differ (see above)");
}

// Two series on the same configuration: (d) SLSQP and Ipopt, (f) exact and FD gradients.
struct PairedCase {
  std::string name;
  Series first, second;
};

// (d): one configuration with its shipped SLSQP settings and with Ipopt's defaults.
PairedCase compareSolvers(const std::string& name, int runs) {
  const OptimizeConfig c = loadOptimizeConfig(std::string(kConfigDir) + name);
  const GaitEvaluator cev(c.robot, c.options, c.model_options);
  OptimizationRequest req = optimizationRequest(c, configuredInitialGuess(c, cev.model()));
  req.solver.print_every = 0;
  PairedCase pc;
  pc.name = name;
  req.solver.backend = Backend::NloptSlsqp;
  pc.first = repeat(cev, req, c.criterion, runs);
  const SolverSettings defaults;
  req.solver.backend = Backend::Ipopt;
  req.solver.ipopt_options.clear();
  req.solver.hessian = defaults.hessian;
  req.solver.constraint_exchange = defaults.constraint_exchange;
  pc.second = repeat(cev, req, c.criterion, runs);
  return pc;
}

void printPairedCases(const std::vector<PairedCase>& cases, const char* first,
                      const char* second, const char* ratio) {
  std::printf("  %-32s %-6s %-10s %10s %8s %8s %10s %18s %6s\n", "config", "run", "status",
              "iterations", "f-evals", "g-evals", "wall [s]", "criterion", "det.");
  for (const PairedCase& pc : cases) {
    for (const auto& [label, s] : {std::pair<const char*, const Series*>{first, &pc.first},
                                   std::pair<const char*, const Series*>{second, &pc.second}}) {
      const Run& r = s->runs.front();
      std::printf("  %-32s %-6s %-10s %10d %8d %8d %10.3f %18s %6s\n", pc.name.c_str(), label,
                  r.status.c_str(), r.iterations, r.function_evaluations,
                  r.gradient_evaluations, s->time.median, criterionText(r.criterion).c_str(),
                  s->deterministic ? "yes" : "NO");
    }
    std::printf("  %-32s ratio %s wall time: %.2f\n", pc.name.c_str(), ratio,
                pc.second.time.median / pc.first.time.median);
  }
}

void writePairedCases(JsonWriter& w, const std::vector<PairedCase>& cases, const char* first,
                      const char* second, const char* ratio_key) {
  w.beginArray();
  for (const PairedCase& pc : cases) {
    w.beginObject();
    w.key("config").value(pc.name);
    w.key(first);
    writeSeries(w, pc.first);
    w.key(second);
    writeSeries(w, pc.second);
    w.key(ratio_key).value(pc.second.time.median / pc.first.time.median);
    w.endObject();
  }
  w.endArray();
}

// (g): the random-start protocol on one shipped configuration.
struct StartProtocol {
  std::string name;
  int starts = 0;
  GlobalSearchResult result;
  Criterion criterion = Criterion::Torque;
  int largest() const {
    int n = 0;
    for (const OptimumCluster& cl : result.clusters) n = std::max(n, cl.size());
    return n;
  }
};

StartProtocol runStartProtocol(const std::string& name, int starts,
                               const RestartSettings& restart_settings) {
  const OptimizeConfig c = loadOptimizeConfig(std::string(kConfigDir) + name);
  const GaitEvaluator cev(c.robot, c.options, c.model_options);
  OptimizationRequest req = optimizationRequest(c, configuredInitialGuess(c, cev.model()));
  req.solver.print_every = 0;
  GlobalSearchSettings gs;
  gs.starts = starts;
  gs.basin_radius = 0.0;
  gs.restart_settings = restart_settings;
  return {name, starts, globalSearch(cev, req, gs), c.criterion};
}

// One line per start: why a start fails (its status, unmet level and groups, violation) and
// the stages it went through, each with the solver's status and iterations.
void printStartTable(const StartProtocol& p) {
  for (const GlobalStart& st : p.result.starts) {
    const OptimizationResult& r = st.result;
    std::string unmet;
    for (const std::string& u : r.unmet_constraints) unmet += (unmet.empty() ? "" : ",") + u;
    std::printf("    start %3d  %-10s level %2d %-28s viol %9.2e  C %s  %.2f s  restarts %d "
                "retries %d perturbed %d\n",
                st.index, optimizationStatusName(r.status), r.unmet_level, unmet.c_str(), r.constraint_violation,
                criterionText(resultCriterion(r, p.criterion)).c_str(), r.wall_time_s, st.restarts,
                st.retries, st.perturbed_restarts);
    for (const StageReport& sr : r.stages)
      std::printf("        %-44s %-10s %4d it\n", sr.name.c_str(), nlpStatusName(sr.status),
                  sr.iterations);
  }
}

void printStartProtocol(const StartProtocol& p) {
  const GlobalSearchResult& g = p.result;
  printStartTable(p);
  std::printf("  %-32s converged %3d/%-3d (%5.1f %%)  clusters %3zu  largest %3d (%5.1f %%)  "
              "median %.3f s/start  best %s\n",
              p.name.c_str(), g.converged, p.starts, 100.0 * g.converged / p.starts,
              g.clusters.size(), p.largest(), 100.0 * p.largest() / p.starts,
              g.median_time_per_start_s,
              criterionText(resultCriterion(g.best, p.criterion)).c_str());
}

void writeStartProtocol(JsonWriter& w, const StartProtocol& p) {
  const GlobalSearchResult& g = p.result;
  w.beginObject();
  w.key("config").value(p.name);
  w.key("starts").value(p.starts);
  w.key("converged").value(g.converged);
  w.key("largest_cluster").value(p.largest());
  w.key("median_time_per_start_s").value(g.median_time_per_start_s);
  w.key("runs").beginArray();
  for (const GlobalStart& st : g.starts) {
    w.beginObject();
    w.key("start").value(st.index);
    w.key("status").value(optimizationStatusName(st.result.status));
    writeNumberOrNull(w, "criterion", resultCriterion(st.result, p.criterion));
    w.key("wall_time_s").value(st.result.wall_time_s);
    w.key("restarts").value(st.restarts);
    w.key("retries").value(st.retries);
    w.key("perturbed_restarts").value(st.perturbed_restarts);
    w.endObject();
  }
  w.endArray();
  writeClusters(w, g.clusters);
  w.endObject();
}

// (g) with --global-per-start K: run s = 1..N is `gaitopt optimize --global K --seed s` (the
// CLI's settings, globalSearchSettings); its final is the polished best, its time the wall time.
struct GlobalRun {
  std::uint64_t seed = 0;
  double wall_s = 0.0;
  OptimizationResult best;
  int optimised = 0;  // starts not skipped by the basin test
};

struct GlobalProtocol {
  std::string name;
  int per_run = 0;  // K
  Criterion criterion = Criterion::Torque;
  std::vector<GlobalRun> runs;
  std::vector<OptimumCluster> clusters;  // of the optimal finals; members index `runs`
  int converged = 0;
};

GlobalProtocol runGlobalProtocol(const std::string& name, int runs, int per_run) {
  const OptimizeConfig c = loadOptimizeConfig(std::string(kConfigDir) + name);
  const GaitEvaluator cev(c.robot, c.options, c.model_options);
  OptimizationRequest req = optimizationRequest(c, configuredInitialGuess(c, cev.model()));
  req.solver.print_every = 0;
  GlobalProtocol p{name, per_run, c.criterion, {}, {}, 0};
  std::vector<double> finals;
  std::vector<int> index;
  for (int s = 1; s <= runs; ++s) {
    const Clock::time_point t0 = Clock::now();
    GlobalSearchResult g = globalSearch(cev, req, globalSearchSettings(per_run, s));
    GlobalRun run{static_cast<std::uint64_t>(s), secondsSince(t0), std::move(g.best),
                  static_cast<int>(g.starts.size()) - g.skipped};
    const std::optional<double> v = resultCriterion(run.best, p.criterion);
    std::printf("    run %3d  %-10s  C %s  %.2f s  optimised %d of %d\n", s,
                optimizationStatusName(run.best.status), criterionText(v).c_str(), run.wall_s, run.optimised,
                per_run);
    if (isOptimal(run.best) && v) {
      finals.push_back(*v);
      index.push_back(s - 1);
    }
    p.runs.push_back(std::move(run));
  }
  p.converged = static_cast<int>(finals.size());
  p.clusters = clusterOptima(finals, GlobalSearchSettings{}.cluster_tolerance);
  for (OptimumCluster& cl : p.clusters)
    for (int& m : cl.members) m = index[m];
  return p;
}

void printGlobalProtocol(const GlobalProtocol& p) {
  const int n = static_cast<int>(p.runs.size());
  std::vector<double> times;
  double optimised = 0.0;
  for (const GlobalRun& r : p.runs) {
    times.push_back(r.wall_s);
    optimised += r.optimised;
  }
  const int best = p.clusters.empty() ? 0 : p.clusters.front().size();
  std::printf("  %-32s --global %d: optimal %3d/%-3d (%5.1f %%)  clusters %3zu  best cluster %3d "
              "(%5.1f %%) at %s  median %.3f s/run  mean %.2f starts optimised\n",
              p.name.c_str(), p.per_run, p.converged, n, 100.0 * p.converged / n,
              p.clusters.size(), best, 100.0 * best / n,
              p.clusters.empty() ? "n/a" : criterionText(p.clusters.front().criterion).c_str(),
              sampleStats(times).median, optimised / n);
  for (const OptimumCluster& cl : p.clusters)
    std::printf("    cluster %s: %d runs\n", criterionText(cl.criterion).c_str(), cl.size());
}

void writeGlobalProtocol(JsonWriter& w, const GlobalProtocol& p) {
  w.beginObject();
  w.key("config").value(p.name);
  w.key("global_per_start").value(p.per_run);
  w.key("converged").value(p.converged);
  w.key("runs").beginArray();
  for (const GlobalRun& r : p.runs) {
    w.beginObject();
    w.key("seed").value(static_cast<int>(r.seed));
    w.key("status").value(optimizationStatusName(r.best.status));
    writeNumberOrNull(w, "criterion", resultCriterion(r.best, p.criterion));
    w.key("wall_time_s").value(r.wall_s);
    w.key("starts_optimised").value(r.optimised);
    w.endObject();
  }
  w.endArray();
  writeClusters(w, p.clusters);
  w.endObject();
}

// Runs (g) alone; exit status as main's.
int startProtocolOnly(int starts, int global_per_start, const std::vector<std::string>& names,
                      const RestartSettings& restart_settings, const std::string& json_path,
                      const Environment& env) {
  if (global_per_start > 0)
    std::printf("(g) --global protocol: %d runs per configuration, run s = `gaitopt optimize "
                "--global %d --seed s`\n", starts, global_per_start);
  else
    std::printf("(g) random-start protocol: %d starts per configuration, seed 1, up to %d "
                "restarts, %d retries and %d perturbed restarts per start\n",
                starts, restart_settings.max_restarts, restart_settings.max_retries,
                restart_settings.max_perturbed_restarts);
  std::vector<StartProtocol> protocols;
  std::vector<GlobalProtocol> global_protocols;
  try {
    for (const std::string& name : names) {
      if (global_per_start > 0) {
        global_protocols.push_back(runGlobalProtocol(name, starts, global_per_start));
        printGlobalProtocol(global_protocols.back());
        continue;
      }
      protocols.push_back(runStartProtocol(name, starts, restart_settings));
      printStartProtocol(protocols.back());
    }
  } catch (const std::exception& e) {
    std::cerr << "bench_optimize: error: " << e.what() << "\n";
    return 2;
  }
  if (json_path.empty()) return 0;
  JsonWriter w;
  w.beginObject();
  writeEnvironment(w, "bench_optimize", env);
  w.key("build").value(std::string(kBuildFlags));
  w.key("random_starts").beginArray();
  for (const StartProtocol& p : protocols) writeStartProtocol(w, p);
  w.endArray();
  w.key("global_protocol").beginArray();
  for (const GlobalProtocol& p : global_protocols) writeGlobalProtocol(w, p);
  w.endArray();
  w.endObject();
  return writeJsonReport("bench_optimize", json_path, w) ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::string json_path;
  int runs = 7, sweep_runs = 3, fd_runs = 3, ipopt_runs = 3, random_starts = 0,
      global_per_start = 0;
  bool with_ipopt = true, with_configs = true, ipopt_only = false;
  std::vector<std::string> start_configs;
  RestartSettings restart_settings;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--help" || arg == "-h") {
      usage(std::cout);
      return 0;
    } else if (arg == "--json" && has_value) {
      json_path = argv[++i];
    } else if (arg == "--runs" && has_value && parsePositive(argv[i + 1], runs) && runs >= 7) {
      ++i;
    } else if (arg == "--sweep-runs" && has_value && parsePositive(argv[i + 1], sweep_runs)) {
      ++i;
    } else if (arg == "--fd-runs" && has_value && parsePositive(argv[i + 1], fd_runs)) {
      ++i;
    } else if (arg == "--no-ipopt") {
      with_ipopt = false;
    } else if (arg == "--ipopt-runs" && has_value && parsePositive(argv[i + 1], ipopt_runs)) {
      ++i;
    } else if (arg == "--ipopt-only") {
      ipopt_only = true;
    } else if (arg == "--random-starts" && has_value &&
               parsePositive(argv[i + 1], random_starts)) {
      ++i;
    } else if (arg == "--global-per-start" && has_value &&
               parsePositive(argv[i + 1], global_per_start)) {
      ++i;
    } else if (arg == "--start-config" && has_value) {
      start_configs.push_back(argv[++i]);
    } else if (arg == "--no-restarts") {
      restart_settings.max_restarts = 0;
    } else if (arg == "--no-retries") {
      restart_settings.max_retries = 0;
    } else if (arg == "--no-perturbed-restarts") {
      restart_settings.max_perturbed_restarts = 0;
    } else if (arg == "--no-configs") {
      with_configs = false;
    } else {
      std::cerr << "bench_optimize: bad argument '" << arg << "'\n";
      usage(std::cerr);
      return 2;
    }
  }

  if (global_per_start > 0 && random_starts == 0) {
    std::cerr << "bench_optimize: --global-per-start needs --random-starts N\n";
    usage(std::cerr);
    return 2;
  }
  if (random_starts > 0) {
    const Environment env;
    printEnvironment("bench_optimize", env);
    if (start_configs.empty())
      start_configs = {"default.yaml", "chesse_0.85.yaml", "chevallereau_aoustin_0.75.yaml"};
    return startProtocolOnly(random_starts, global_per_start, start_configs, restart_settings,
                             json_path, env);
  }
  const std::string default_path = std::string(kConfigDir) + "default.yaml";
  std::optional<OptimizeConfig> config;
  std::optional<GaitEvaluator> evaluator;
  try {
    config.emplace(loadOptimizeConfig(default_path));
    evaluator.emplace(config->robot, config->options, config->model_options);
  } catch (const std::exception& e) {
    std::cerr << "bench_optimize: error: " << e.what() << "\n";
    return 2;
  }
  const GaitEvaluator& ev = *evaluator;
  const Criterion criterion = config->criterion;
  const OptimizationRequest request =
      optimizationRequest(*config, configuredInitialGuess(*config, ev.model()));
  const Environment env;
  const Clock::time_point start = Clock::now();
  bool deterministic = true;

  printEnvironment("bench_optimize", env);
  // (d) Ipopt vs SLSQP on the shipped configurations.
  std::vector<PairedCase> solver_cases;
  // false (after printing the error) when a configuration cannot be read.
  const auto runSolverComparison = [&]() -> bool {
    std::printf("(d) Ipopt (library defaults) vs SLSQP (as shipped), %d runs each; wall time: "
                "median\n", ipopt_runs);
    std::vector<std::string> names = {"default.yaml"};
    if (with_configs) {
      names.push_back("chesse_0.85.yaml");
      names.push_back("chevallereau_aoustin_0.75.yaml");
    }
    try {
      for (const std::string& name : names) solver_cases.push_back(compareSolvers(name, ipopt_runs));
    } catch (const std::exception& e) {
      std::cerr << "bench_optimize: error: " << e.what() << "\n";
      return false;
    }
    printPairedCases(solver_cases, "slsqp", "ipopt", "Ipopt / SLSQP");
    std::printf("\n");
    for (const PairedCase& pc : solver_cases)
      deterministic = deterministic && pc.first.deterministic && pc.second.deterministic;
    return true;
  };
  if (ipopt_only) {
    if (!runSolverComparison()) return 2;
    if (!json_path.empty()) {
      JsonWriter w;
      w.beginObject();
      writeEnvironment(w, "bench_optimize", env);
      w.key("build").value(std::string(kBuildFlags));
      w.key("deterministic").value(deterministic);
      w.key("ipopt_vs_slsqp");
      writePairedCases(w, solver_cases, "slsqp", "ipopt", "ratio_ipopt_to_slsqp");
      w.endObject();
      if (!writeJsonReport("bench_optimize", json_path, w)) return 1;
    }
    return deterministic ? 0 : 1;
  }
  std::printf("config:    %s (robot %s, criterion %s, speed %s m/s, backend %s, hierarchy %s, "
              "constraint_exchange %s)\n\n",
              default_path.c_str(), config->robot_path.c_str(), criterionName(criterion),
              config->speed ? std::to_string(*config->speed).c_str() : "free",
              backendName(config->solver.backend), strategyName(config->solver.hierarchy),
              config->solver.constraint_exchange ? "true" : "false");

  // (a) the configured optimisation, exact gradients.
  std::printf("(a) optimizeGait, configured start: 1 warm-up + %d timed runs\n", runs);
  const Run warmup = runOnce(ev, request, criterion);
  Series exact = repeat(ev, request, criterion, runs);
  if (!sameOutcome(warmup, exact.runs.front())) exact.deterministic = false;
  std::printf("  warm-up:  %8.3f s  status %-10s  C_Gamma %s\n", warmup.wall_s,
              warmup.status.c_str(), criterionText(warmup.criterion).c_str());
  printSeriesRuns("exact", exact);
  deterministic = deterministic && exact.deterministic;
  std::printf("  wall time [s]: median %.3f  min %.3f  p90 %.3f   target median <= %.1f s: %s\n\n",
              exact.time.median, exact.time.min, exact.time.p90, kOptimizeTargetS,
              verdict(exact.time.median, kOptimizeTargetS));

  // (b) the 9-speed sweep, built as `gaitopt sweep` builds it.
  OptimizeConfig free_config = *config;
  free_config.speed.reset();
  free_config.options.target_speed = 0.0;
  const GaitEvaluator free_ev(free_config.robot, free_config.options, free_config.model_options);
  const OptimizationRequest base =
      optimizationRequest(free_config, configuredInitialGuess(free_config, free_ev.model()));
  const std::vector<double> speeds = parseSpeedRange(kSweepSpeeds);
  SweepSettings sweep_settings;
  sweep_settings.jobs = 1;
  std::printf("(b) sweepSpeeds %s (%zu speeds), jobs 1: %d timed runs\n", kSweepSpeeds,
              speeds.size(), sweep_runs);
  std::vector<SweepRun> sweeps;
  bool sweep_deterministic = true;
  for (int i = 0; i < sweep_runs; ++i) {
    const Clock::time_point t0 = Clock::now();
    const std::vector<SweepPoint> points = sweepSpeeds(free_ev, base, speeds, sweep_settings);
    SweepRun s;
    s.wall_s = secondsSince(t0);
    for (const SweepPoint& p : points) {
      s.speeds.push_back(p.speed);
      s.status.push_back(optimizationStatusName(p.result.status));
      s.criterion.push_back(resultCriterion(p.result, criterion));
      s.attempts.push_back(p.attempts);
      if (isOptimal(p.result)) ++s.optimal;
    }
    if (!sweeps.empty() &&
        (s.status != sweeps.front().status || s.criterion != sweeps.front().criterion))
      sweep_deterministic = false;
    std::printf("  sweep run %d: %8.3f s  %d/%zu optimal\n", i + 1, s.wall_s, s.optimal,
                points.size());
    sweeps.push_back(std::move(s));
  }
  deterministic = deterministic && sweep_deterministic;
  std::vector<double> sweep_times;
  for (const SweepRun& s : sweeps) sweep_times.push_back(s.wall_s);
  const SampleStats sweep_time = sampleStats(sweep_times);
  const SweepRun& first_sweep = sweeps.front();
  for (std::size_t k = 0; k < first_sweep.speeds.size(); ++k)
    std::printf("    v=%.3f m/s  %-10s  C_Gamma %-16s  %d attempt%s\n", first_sweep.speeds[k],
                first_sweep.status[k].c_str(), criterionText(first_sweep.criterion[k]).c_str(),
                first_sweep.attempts[k], first_sweep.attempts[k] == 1 ? "" : "s");
  std::printf("  sweeps: %s\n", sweep_deterministic
                                    ? "deterministic (same statuses, C_Gamma bit-identical)"
                                    : "NON-DETERMINISTIC: runs differ");
  std::printf("  total wall time [s]: median %.3f  min %.3f  max %.3f   optimal %d/%zu   "
              "target median <= %.1f s: %s\n\n",
              sweep_time.median, sweep_time.min, sweep_time.max, first_sweep.optimal,
              speeds.size(), kSweepTargetS, verdict(sweep_time.median, kSweepTargetS));

  // (c) peak resident memory so far.
  rusage usage_after{};
  getrusage(RUSAGE_SELF, &usage_after);
  const double peak_rss_mib = static_cast<double>(usage_after.ru_maxrss) / 1024.0;  // kB on Linux
  std::printf("(c) peak resident set size after the sweeps (ru_maxrss): %.1f MiB\n\n",
              peak_rss_mib);

  if (with_ipopt && !runSolverComparison()) return 2;

  // (e) finite-difference gradients, SLSQP.
  OptimizationRequest fd_request = request;
  fd_request.solver.gradients = GradientMode::FiniteDifference;
  std::printf("(e) optimizeGait with GradientMode::FiniteDifference (SLSQP): %d runs\n", fd_runs);
  const Series fd = repeat(ev, fd_request, criterion, fd_runs);
  printSeriesRuns("fd", fd);
  deterministic = deterministic && fd.deterministic;
  std::printf("  wall time [s]: median %.3f  min %.3f   ratio FD / exact (medians): %.2f\n\n",
              fd.time.median, fd.time.min, fd.time.median / exact.time.median);

  // (f) exact vs finite differences on the three shipped SLSQP configurations.
  std::vector<PairedCase> cases = {{"default.yaml", exact, fd}};
  if (with_configs) {
    for (const char* name : {"chesse_0.85.yaml", "chevallereau_aoustin_0.75.yaml"}) {
      try {
        const OptimizeConfig c = loadOptimizeConfig(std::string(kConfigDir) + name);
        const GaitEvaluator cev(c.robot, c.options, c.model_options);
        OptimizationRequest req = optimizationRequest(c, configuredInitialGuess(c, cev.model()));
        PairedCase gc;
        gc.name = name;
        gc.first = repeat(cev, req, c.criterion, fd_runs);
        req.solver.gradients = GradientMode::FiniteDifference;
        gc.second = repeat(cev, req, c.criterion, fd_runs);
        deterministic = deterministic && gc.first.deterministic && gc.second.deterministic;
        cases.push_back(std::move(gc));
      } catch (const std::exception& e) {
        std::cerr << "bench_optimize: error: " << e.what() << "\n";
        return 2;
      }
    }
  }
  std::printf("(f) exact vs finite-difference gradients (SLSQP; wall time: median)\n");
  printPairedCases(cases, "exact", "fd", "FD / exact");

  const double total_s = secondsSince(start);
  std::printf("\ntotal benchmark time %.1f s; %s\n(sink %g)\n", total_s,
              deterministic ? "every repeated measurement deterministic"
                            : "NON-DETERMINISM detected (exit status 1)",
              static_cast<double>(g_sink));

  if (!json_path.empty()) {
    JsonWriter w;
    w.beginObject();
    writeEnvironment(w, "bench_optimize", env);
    w.key("build").value(std::string(kBuildFlags));
    w.key("config").value(default_path);
    w.key("criterion").value(criterionName(criterion));
    w.key("deterministic").value(deterministic);
    w.key("total_time_s").value(total_s);
    w.key("optimize").beginObject();
    w.key("target_median_s").value(kOptimizeTargetS);
    w.key("target_met").value(exact.time.median <= kOptimizeTargetS);
    w.key("warmup");
    writeRun(w, warmup);
    w.key("timed");
    writeSeries(w, exact);
    w.endObject();
    w.key("sweep").beginObject();
    w.key("speeds").value(std::string(kSweepSpeeds));
    w.key("jobs").value(1);
    w.key("count").value(static_cast<int>(sweeps.size()));
    w.key("median_s").value(sweep_time.median);
    w.key("min_s").value(sweep_time.min);
    w.key("max_s").value(sweep_time.max);
    w.key("target_median_s").value(kSweepTargetS);
    w.key("target_met").value(sweep_time.median <= kSweepTargetS);
    w.key("optimal").value(first_sweep.optimal);
    w.key("total").value(static_cast<int>(speeds.size()));
    w.key("deterministic").value(sweep_deterministic);
    w.key("wall_times_s").beginArray();
    for (double t : sweep_times) w.value(t);
    w.endArray();
    w.key("points").beginArray();
    for (std::size_t k = 0; k < first_sweep.speeds.size(); ++k) {
      w.beginObject();
      w.key("speed").value(first_sweep.speeds[k]);
      w.key("status").value(first_sweep.status[k]);
      writeNumberOrNull(w, "criterion", first_sweep.criterion[k]);
      w.key("attempts").value(first_sweep.attempts[k]);
      w.endObject();
    }
    w.endArray();
    w.endObject();
    w.key("peak_rss_mib").value(peak_rss_mib);
    w.key("ipopt_vs_slsqp");
    writePairedCases(w, solver_cases, "slsqp", "ipopt", "ratio_ipopt_to_slsqp");
    w.key("finite_difference").beginObject();
    w.key("timed");
    writeSeries(w, fd);
    w.key("ratio_to_exact").value(fd.time.median / exact.time.median);
    w.endObject();
    w.key("gradient_comparison");
    writePairedCases(w, cases, "exact", "finite_difference", "ratio_fd_to_exact");
    w.endObject();
    if (!writeJsonReport("bench_optimize", json_path, w)) return 1;
  }
  return deterministic ? 0 : 1;
}
