// `gaitopt sweep`: optimal steps over a list of walking speeds by continuation
// (opt/continuation.hpp)
// → OUT/sweep.csv and one folder per speed (summary.json, gait.yaml, trajectory.csv, as written
// by `gaitopt optimize`); `gaitopt sweep-merge`: the sweep.csv of several shards in one file.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "override_options.hpp"
#include "commands.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/sweep_file.hpp"

namespace gaitopt::cli {
namespace {

namespace fs = std::filesystem;

struct SweepArgs {
  std::string config, speeds, out;
  OverrideArgs overrides;
  int jobs = 1;
  std::optional<std::string> shard;
  bool quiet = false;
};

struct MergeArgs {
  std::string out;
  std::vector<std::string> shards;
};

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
  addOverrideOptions(cmd, args->overrides, nullptr);
  cmd->add_option("--speeds", args->speeds,
                  "Speeds start:stop:step [m/s], stop included, e.g. 0.2:1.0:0.05")
      ->required();
  cmd->add_option("--out", args->out, "Output directory (created if missing)")->required();
  cmd->add_option("--jobs", args->jobs,
                  "Independent continuation chains on contiguous chunks of the speeds, one "
                  "thread each (default 1; ipopt: run one after the other)")
      ->check(integerWithin(1, 1024));
  cmd->add_option("--shard", args->shard,
                  "i/n: only the i-th (0-based) of n contiguous chunks of the speeds")
      ->type_name("I/N");
  cmd->add_flag("--quiet", args->quiet, "No per-speed progress lines");
  cmd->callback([args, &exit_code]() {
    // Everything that can fail on bad input happens before the output directory is touched.
    OptimizeConfig config = loadOptimizeConfigWithOverrides(args->config, overridesOf(args->overrides, nullptr));
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
    OutputTransaction output({{"--config", args->config}});
    const fs::path stage = output.directory("--out", args->out, ourOutputs(&config.solver));
    placeIpoptOutputFile(config.solver, stage.string());
    if (config.speed)
      std::cerr << "gaitopt: sweep: note: the config's speed ("
                << shortNumber(*config.speed, "%g")
                << " m/s) is ignored; the sweep sets each speed\n";

    // The free-speed problem of the config: no target speed, the configured initial guess
    // (a gait file, or defaultInitialGuess without a speed).
    const OptimizeConfig free_config = freeSpeedConfig(config);
    const GaitEvaluator evaluator(free_config.robot, free_config.options,
                                  free_config.model_options);
    const OptimizationRequest base =
        optimizationRequest(free_config, configuredInitialGuess(free_config, evaluator.model()));
    const Criterion criterion = config.criterion;
    const int decimals = sweepFolderDecimals(speeds);  // of the whole list: shards agree
    const fs::path out(args->out);

    // "v=<speed> m/s  status <status>  <criterion> <value> <unit>  worst <constraint> +<value>
    // <unit>  elapsed <time> s, remaining ~<time> s"
    const auto progressLine = [&](const SweepProgress& p) {
      const OptimizationResult& r = p.point.result;
      return "v=" + shortNumber(p.point.speed, "%.3f") + " m/s  status " +
             optimizationStatusName(r.status) + "  " +
             progressText(evaluator, r.evaluation, criterion) + "  " +
             sweepEvidenceText(p.point) + elapsedAndRemaining(p.elapsed_s, p.done, p.total);
    };
    auto progress = [&](const SweepProgress& p) {
      if (p.free_speed) {
        if (!args->quiet) std::cout << "free speed: " << progressLine(p) << "\n" << std::flush;
        return;
      }
      const std::string folder = sweepFolderName(p.point.speed, decimals);
      writeOptimizationOutputs((stage / folder).string(),
                               sweepPointOutputs(config, p.point, (out / folder).string()));
      if (!args->quiet)
        std::cout << "[" << p.done << "/" << p.total << "] " << progressLine(p)
                  << (p.point.attempts > 1 ? "  (" + std::to_string(p.point.attempts) + " attempts)"
                                           : "")
                  << "\n"
                  << std::flush;
    };
    const std::vector<SweepPoint> points = sweepSpeeds(evaluator, base, speeds, settings, progress);
    writeNewFile((stage / "sweep.csv").string(), sweepCsv(evaluator, points));
    output.commit();

    std::vector<std::string> failed;
    for (const SweepPoint& p : points)
      if (!isOptimal(p.result))
        failed.push_back(shortNumber(p.speed, "%g") + " m/s (" +
                         optimizationStatusName(p.result.status) + ")");
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
    std::string merged;
    try {
      merged = mergeShardSweepCsvs(args->shards);
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError("SHARD_DIR", e.what());
    }
    const fs::path out(args->out);
    std::vector<RunInput> inputs;
    for (const std::string& shard : args->shards)
      inputs.push_back({"SHARD_DIR", (fs::path(shard) / "sweep.csv").string()});
    OutputTransaction output(inputs);
    requireOwnDirectory("--out", args->out);
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec) throw OutputError("--out '" + args->out + "' cannot be created: " + ec.message());
    writeNewFile(output.file("--out", (out / "sweep.csv").string()), merged);
    output.commit();
    const SweepCsvCount n = countSweepCsvRows(merged);
    std::cout << "sweep-merge: " << n.rows << " speeds (" << n.optimal << " optimal) from "
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
