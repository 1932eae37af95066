// `gaitopt sweep`: optimal steps over a list of walking speeds by continuation (opt/sweep.hpp)
// → OUT/sweep.csv and one folder per speed (summary.json, gait.yaml, trajectory.csv, as written
// by `gaitopt optimize`); `gaitopt sweep-merge`: the sweep.csv of several shards in one file.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/io/atomic_file.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/summary.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/io/optimize_output.hpp"
#include "gaitopt/opt/sweep.hpp"

namespace gaitopt::cli {
namespace {

namespace fs = std::filesystem;

struct SweepArgs {
  std::string config;
  std::string speeds;
  std::string out;
  int jobs = 1;
  std::optional<std::string> shard;
  bool quiet = false;
};

struct MergeArgs {
  std::string out;
  std::vector<std::string> shards;
};

// The sweep's own members of a speed's summary.json.
void writeSweepMembers(JsonWriter& w, const SweepPoint& p) {
  w.key("sweep").beginObject();
  w.key("speed").value(p.speed);
  w.key("warm_started").value(p.warm_started);
  w.key("from_speed").value(p.from_speed);  // null (NaN) when started from the default guess
  w.key("attempts").value(p.attempts);
  w.key("total_iterations").value(p.total_iterations);
  w.key("total_wall_time_s").value(p.total_wall_time_s);
  w.endObject();
}

// A shard's sweep.csv: a regular file within the size limit (a directory would read as empty).
std::string readText(const fs::path& path) {
  const std::string name = printable(path.string());
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw CLI::ValidationError("SHARD_DIR", "'" + name + "' is missing or not a regular file");
  if (fs::file_size(path, ec) > kMaxSweepCsvBytes)
    throw CLI::ValidationError("SHARD_DIR", "'" + name + "' is larger than " +
                                                std::to_string(kMaxSweepCsvBytes) +
                                                " bytes (limit)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CLI::ValidationError("SHARD_DIR", "cannot read '" + name + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void registerSweep(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Optimise walking steps over a range of speeds by continuation from the free-speed "
      "optimum: writes OUT/sweep.csv and OUT/v<speed>/{summary.json,gait.yaml,trajectory.csv}. "
      "The config's `speed` is ignored. Exit 0: every speed optimal; 3: some not (listed); 2: "
      "bad input (nothing written).");
  cmd->add_option("--config", args->config,
                  "Optimiser configuration YAML file (as for `gaitopt optimize`)")
      ->required();
  cmd->add_option("--speeds", args->speeds,
                  "Speeds start:stop:step [m/s], stop included, e.g. 0.2:1.0:0.05")
      ->required();
  cmd->add_option("--out", args->out, "Output directory (created if missing)")->required();
  cmd->add_option("--jobs", args->jobs,
                  "Independent continuation chains on contiguous chunks of the speeds, one "
                  "thread each (default 1; ipopt: run one after the other)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--shard", args->shard,
                  "i/n: only the i-th (0-based) of n contiguous chunks of the speeds")
      ->type_name("I/N");
  cmd->add_flag("--quiet", args->quiet, "No per-speed progress lines");
  cmd->callback([args, &exit_code]() {
    // Everything that can fail on bad input happens before the output directory is touched.
    OptimizeConfig config = loadOptimizeConfig(args->config);
    std::vector<double> speeds;
    try {
      speeds = sortedSpeeds(parseSpeedRange(args->speeds));
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError("--speeds", e.what());
    }
    SweepSettings settings;
    settings.jobs = args->jobs;
    settings.warnings = &std::cerr;
    std::vector<double> run;
    try {
      if (args->shard) {
        settings.sharded = true;
        settings.shard = parseShard(*args->shard);
      }
      run = sweepRunSpeeds(speeds, settings);
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError("--shard", e.what());
    }
    // The whole sweep is written beside --out and put in place at the end (checked here,
    // before any work): an interrupted re-run leaves the previous sweep complete.
    StagedDirectory staged(args->out, ourOutputs(&config.solver));
    placeIpoptOutputFile(config.solver, staged.path());
    if (config.speed)
      std::cerr << "gaitopt: sweep: note: the config's speed ("
                << shortNumber(*config.speed, "%g")
                << " m/s) is ignored; the sweep sets each speed\n";

    // The free-speed problem of the config: no target speed, the configured initial guess
    // (a gait file, or defaultInitialGuess without a speed).
    OptimizeConfig free_config = config;
    free_config.speed.reset();
    free_config.options.target_speed = 0.0;
    const GaitEvaluator evaluator(free_config.robot, free_config.options,
                                  free_config.model_options);
    const OptimizationRequest base =
        optimizationRequest(free_config, configuredInitialGuess(free_config, evaluator.model()));
    const Criterion criterion = config.criterion;
    const int decimals = sweepFolderDecimals(speeds);  // of the whole list: shards agree
    const fs::path out(args->out), stage(staged.path());

    // "v=<speed> m/s  status <status>  <criterion> <value> <unit>  worst <constraint> +<value>
    // <unit>  elapsed <time> s, remaining ~<time> s"
    const auto progressLine = [&](const SweepProgress& p) {
      const OptimizationResult& r = p.point.result;
      return "v=" + shortNumber(p.point.speed, "%.3f") + " m/s  status " + r.status + "  " +
             progressText(evaluator, r.evaluation, criterion) + "  " +
             elapsedAndRemaining(p.elapsed_s, p.done, p.total);
    };
    auto progress = [&](const SweepProgress& p) {
      const OptimizationResult& r = p.point.result;
      if (p.free_speed) {
        if (!args->quiet) std::cout << "free speed: " << progressLine(p) << "\n" << std::flush;
        return;
      }
      // The speed's outputs, as `gaitopt optimize` with `speed` set to it would write them.
      OptimizeConfig speed_config = config;
      speed_config.speed = p.point.speed;
      speed_config.options.target_speed = p.point.speed;
      const GaitEvaluator speed_evaluator(speed_config.robot, speed_config.options,
                                          speed_config.model_options);
      const std::string folder = sweepFolderName(p.point.speed, decimals);
      writeOptimizationOutputs(
          (stage / folder).string(),
          optimizationOutputs(speed_evaluator, speed_config, r, (out / folder).string(),
                              [&](JsonWriter& w) { writeSweepMembers(w, p.point); }));
      if (!args->quiet)
        std::cout << "[" << p.done << "/" << p.total << "] " << progressLine(p)
                  << (p.point.attempts > 1 ? "  (" + std::to_string(p.point.attempts) + " attempts)"
                                           : "")
                  << "\n"
                  << std::flush;
    };
    const std::vector<SweepPoint> points = sweepSpeeds(evaluator, base, speeds, settings, progress);
    writeFileAtomically((stage / "sweep.csv").string(), sweepCsv(evaluator, points));
    staged.commit();

    std::vector<std::string> failed;
    for (const SweepPoint& p : points)
      if (p.result.status != "optimal")
        failed.push_back(shortNumber(p.speed, "%g") + " m/s (" + p.result.status + ")");
    std::cout << "sweep: " << points.size() - failed.size() << "/" << points.size()
              << " speeds optimal -> " << (out / "sweep.csv").string() << "\n";
    if (failed.empty()) {
      exit_code = 0;
      return;
    }
    std::cerr << "gaitopt: sweep: not optimal:";
    for (std::size_t i = 0; i < failed.size(); ++i) std::cerr << (i ? ", " : " ") << failed[i];
    std::cerr << "\n";
    exit_code = kExitUndefined;
  });
}

void registerSweepMerge(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sweep-merge",
      "Merge the sweep.csv of several `gaitopt sweep --shard` output directories into "
      "OUT/sweep.csv (rows sorted by speed; the per-speed folders stay in the shard "
      "directories). Exit 0: merged; 2: bad input (differing headers, a speed twice, a missing "
      "sweep.csv; nothing written).");
  cmd->add_option("--out", args->out, "Output directory (created if missing)")->required();
  cmd->add_option("SHARD_DIR", args->shards, "Output directories of the shards")
      ->required()
      ->expected(1, -1);
  cmd->callback([args, &exit_code]() {
    std::vector<std::string> texts, names;
    for (const std::string& dir : args->shards) {
      const fs::path csv = fs::path(dir) / "sweep.csv";
      names.push_back(csv.string());
      texts.push_back(readText(csv));
    }
    std::string merged;
    try {
      merged = mergeSweepCsvs(texts, names);
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError("SHARD_DIR", e.what());
    }
    requireDirectoryOrAbsent(args->out);
    const fs::path out(args->out);
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) throw OutputError("--out '" + args->out + "' cannot be created: " + ec.message());
    writeFileAtomically((out / "sweep.csv").string(), merged);
    std::size_t rows = 0, optimal = 0;
    std::istringstream in(merged);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      ++rows;
      if (line.find(",optimal,") != std::string::npos) ++optimal;
    }
    std::cout << "sweep-merge: " << rows << " speeds (" << optimal << " optimal) from "
              << args->shards.size() << " shard(s) -> " << (out / "sweep.csv").string() << "\n";
    exit_code = 0;
  });
}

}  // namespace

void registerSweepCommands(CLI::App& app, int& exit_code) {
  registerSweep(app, exit_code);
  registerSweepMerge(app, exit_code);
}

}  // namespace gaitopt::cli
