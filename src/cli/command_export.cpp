// `gaitopt export`: N steps of a gait for a joint-level controller, as CSV or JSON.
#include <iostream>
#include <memory>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/io/atomic_file.hpp"

namespace gaitopt::cli {
namespace {

struct ExportArgs {
  std::string gait, out, format = "csv", first_stance = "left";
  int steps = 10;
  double rate = 1000.0;
};

}  // namespace

void registerExportCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Export N consecutive steps of a gait (alternating physical stance leg) at a fixed rate "
      "for a controller: phase variable, motor angles, feedforward torques split into parts, "
      "feet and planned reactions. Exit 3 if the gait is undefined, 2 on bad input.");
  cmd->add_option("--gait", args->gait, "Gait YAML file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "Output file")->required();
  cmd->add_option("--steps", args->steps, "Number of steps (>= 1)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--rate", args->rate, "Sample rate [Hz] (0 < HZ <= 1e5)")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 1e5));
  cmd->add_option("--format", args->format, "csv or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"csv", "json"}));
  cmd->add_option("--first-stance", args->first_stance, "Physical stance leg of step 0")
      ->capture_default_str()
      ->check(CLI::IsMember({"left", "right"}));
  cmd->callback([args, &exit_code]() {
    const GaitFile gait = loadGaitFile(args->gait);
    requireFileOutput(args->out);
    const GaitEvaluator evaluator(gait.robot, gait.options, gait.model_options);
    const GaitEvaluation<double> e = evaluator.evaluate(gait.parameters);
    if (!e.defined() || !e.motion_computed) {
      std::cerr << "gaitopt: error: " << args->gait << ": the step is undefined (failed level "
                << e.failed_level << "); nothing exported\n";
      exit_code = kExitUndefined;
      return;
    }
    ExportRequest req;
    req.steps = args->steps;
    req.rate = args->rate;
    req.first_stance = args->first_stance == "left" ? Leg::Left : Leg::Right;
    // The feedforward overcomes the robot file's whole friction, not only the optimised part.
    const Model model = buildModel(gait.robot, gait.model_options);
    const std::vector<ExportRow> rows = exportTrajectory(evaluator, e, model, req);
    const ExportMetadata meta = exportMetadata(gait, e, req);
    writeFileAtomically(args->out, args->format == "csv" ? exportCsv(meta, rows)
                                                         : exportJson(meta, rows, e));
    std::cout << "export: " << args->steps << " steps, " << rows.size() << " samples at "
              << shortNumber(args->rate) << " Hz, speed " << shortNumber(e.speed, "%.4g")
              << " m/s -> " << args->out << "\n";
    exit_code = 0;
  });
}

}  // namespace gaitopt::cli
