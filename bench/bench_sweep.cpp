// bench_sweep: the speed library of `gaitopt sweep` (TROPIC's RABBIT benchmark: 10 gaits,
// 0.15–1.05 m/s) on configs/default.yaml.
//
//   bench_sweep [--runs N] [--speeds START:STOP:STEP] [--config NAME] [--json FILE] [--help]
//
// sweepSpeeds over the speeds (default 0.15:1.05:0.1), one chain, built as `gaitopt sweep`
// builds it (free-speed evaluator, configured start without a speed), `runs` times (default
// 3, at least 3): the median wall time and process CPU time of a whole library against the
// target (1.5 s), the free-speed optimisation's share; then, from the first run, one line per
// speed: status, C_Gamma, attempts, solver iterations (the elastic problem's included), wall
// time, milliseconds per iteration, and for a speed without an optimum what the elastic
// problem showed (opt/infeasibility_certificate.hpp). Every run must give the same statuses
// and bit-identical criteria. CPU time is the figure on a shared machine (wall time counts
// the other processes' share). Exit status: 0, 1 when the runs differ (or the JSON file cannot
// be written), 2 for bad arguments or an unreadable configuration.
#include <chrono>
#include <cstdio>
#include <ctime>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/io/sweep_file.hpp"

namespace {

using namespace gaitopt;
using namespace gaitopt::bench;

constexpr double kLibraryTargetS = 1.5;

struct LibraryRun {
  double wall_s = 0.0, cpu_s = 0.0, free_speed_s = 0.0;
  std::vector<SweepPoint> points;
};

double processCpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

LibraryRun runLibrary(const GaitEvaluator& ev, const OptimizationRequest& base,
                      const std::vector<double>& speeds) {
  LibraryRun run;
  const double cpu0 = processCpuSeconds();
  const Clock::time_point t0 = Clock::now();
  run.points = sweepSpeeds(ev, base, speeds, SweepSettings{}, [&](const SweepProgress& p) {
    if (p.free_speed) run.free_speed_s = p.elapsed_s;
  });
  run.wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
  run.cpu_s = processCpuSeconds() - cpu0;
  return run;
}

bool sameOutcome(const LibraryRun& a, const LibraryRun& b) {
  if (a.points.size() != b.points.size()) return false;
  for (std::size_t i = 0; i < a.points.size(); ++i)
    if (a.points[i].result.status != b.points[i].result.status ||
        a.points[i].result.evaluation.C_Gamma != b.points[i].result.evaluation.C_Gamma)
      return false;
  return true;
}

int optimalCount(const LibraryRun& r) {
  int n = 0;
  for (const SweepPoint& p : r.points) n += isOptimal(p.result) ? 1 : 0;
  return n;
}

double msPerIteration(const SweepPoint& p) {
  return p.total_iterations > 0 ? 1e3 * p.total_wall_time_s / p.total_iterations : 0.0;
}

void writeJson(JsonWriter& w, const Environment& env, const std::string& config,
               const std::string& speeds, const std::vector<LibraryRun>& runs,
               const SampleStats& wall, const SampleStats& cpu, bool deterministic) {
  w.beginObject();
  writeEnvironment(w, "bench_sweep", env);
  w.key("config").value(config);
  w.key("speeds").value(speeds);
  w.key("runs").value(static_cast<int>(runs.size()));
  w.key("deterministic").value(deterministic);
  w.key("median_wall_s").value(wall.median);
  w.key("median_cpu_s").value(cpu.median);
  w.key("median_free_speed_s").value(sampleStats([&] {
    std::vector<double> v;
    for (const LibraryRun& r : runs) v.push_back(r.free_speed_s);
    return v;
  }()).median);
  w.key("target_s").value(kLibraryTargetS);
  w.key("optimal").value(static_cast<int>(optimalCount(runs.front())));
  w.key("points").beginArray();
  for (const SweepPoint& p : runs.front().points) {
    w.beginObject();
    w.key("speed").value(p.speed);
    w.key("status").value(optimizationStatusName(p.result.status));
    w.key("C_Gamma").value(p.result.evaluation.C_Gamma);
    w.key("attempts").value(static_cast<int>(p.attempts));
    w.key("iterations").value(static_cast<int>(p.total_iterations));
    w.key("wall_time_s").value(p.total_wall_time_s);
    w.key("ms_per_iteration").value(msPerIteration(p));
    w.key("evidence").value(sweepEvidenceText(p));
    w.endObject();
  }
  w.endArray();
  w.endObject();
}

void usage(std::ostream& out) {
  out << "usage: bench_sweep [--runs N] [--speeds START:STOP:STEP] [--config NAME] [--json FILE]\n"
         "  --runs N      timed libraries (default 3, at least 3)\n"
         "  --speeds R    the speed range (default 0.15:1.05:0.1)\n"
         "  --config NAME configs/NAME (default default.yaml)\n"
         "  --json FILE   also write the results as JSON to FILE\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string json_path, speeds_text = "0.15:1.05:0.1", config_name = "default.yaml";
  int runs = 3;
  // Each option but --help takes one value.
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      usage(std::cout);
      return 0;
    }
    const char* value = i + 1 < argc ? argv[++i] : nullptr;
    bool ok = value != nullptr;
    if (ok && arg == "--json")
      json_path = value;
    else if (ok && arg == "--runs")
      ok = parsePositive(value, runs) && runs >= 3;
    else if (ok && arg == "--speeds")
      speeds_text = value;
    else if (ok && arg == "--config")
      config_name = value;
    else
      ok = false;
    if (!ok) {
      std::cerr << "bench_sweep: bad argument '" << arg << "'\n";
      usage(std::cerr);
      return 2;
    }
  }
  std::vector<double> speeds;
  OptimizeConfig free_config;
  const std::string config_path = std::string(GAITOPT_SOURCE_DIR "/configs/") + config_name;
  try {
    speeds = parseSpeedRange(speeds_text);
    free_config = freeSpeedConfig(loadOptimizeConfig(config_path));
  } catch (const std::exception& e) {
    std::cerr << "bench_sweep: " << e.what() << "\n";
    return 2;
  }
  const Environment env;
  printEnvironment("bench_sweep", env);
  const GaitEvaluator ev(free_config.robot, free_config.options, free_config.model_options);
  const OptimizationRequest base =
      optimizationRequest(free_config, configuredInitialGuess(free_config, ev.model()));
  std::printf("config:    %s, speeds %s (%zu), one chain, %d runs\n\n", config_path.c_str(),
              speeds_text.c_str(), speeds.size(), runs);

  std::vector<LibraryRun> library;
  std::vector<double> walls, cpus;
  bool deterministic = true;
  for (int i = 0; i < runs; ++i) {
    library.push_back(runLibrary(ev, base, speeds));
    const LibraryRun& r = library.back();
    deterministic = deterministic && sameOutcome(r, library.front());
    walls.push_back(r.wall_s);
    cpus.push_back(r.cpu_s);
    std::printf("run %d: wall %.3f s  cpu %.3f s  free speed %.3f s  %d/%zu optimal\n", i + 1,
                r.wall_s, r.cpu_s, r.free_speed_s, optimalCount(r), r.points.size());
  }
  const SampleStats wall = sampleStats(walls), cpu = sampleStats(cpus);
  std::printf("library: median wall %.3f s, median cpu %.3f s   target <= %.1f s: %s\n",
              wall.median, cpu.median, kLibraryTargetS, verdict(cpu.median, kLibraryTargetS));
  std::printf("runs: %s\n\n", deterministic ? "same statuses and criteria"
                                            : "DIFFER (statuses or criteria)");
  std::printf("%-7s %-10s %-12s %8s %6s %8s %7s  %s\n", "v [m/s]", "status", "C_Gamma",
              "attempts", "iter", "time [s]", "ms/iter", "evidence");
  for (const SweepPoint& p : library.front().points)
    std::printf("%-7.3f %-10s %-12.6g %8d %6d %8.3f %7.2f  %s\n", p.speed,
                optimizationStatusName(p.result.status), p.result.evaluation.C_Gamma,
                p.attempts, p.total_iterations, p.total_wall_time_s, msPerIteration(p),
                sweepEvidenceText(p).c_str());
  if (!json_path.empty()) {
    JsonWriter w;
    writeJson(w, env, config_name, speeds_text, library, wall, cpu, deterministic);
    if (!writeJsonReport("bench_sweep", json_path, w)) return 1;
  }
  return deterministic ? 0 : 1;
}
