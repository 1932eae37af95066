// `gaitopt import-opensim`: OpenSim IK + GRF (+ markers) → measured-data CSV at the GRF rate,
// or a result folder with that CSV and the point-foot analysis of the trial as JSON.
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "cli_common.hpp"
#include "commands.hpp"
#include "data_files.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/opensim_analysis_file.hpp"
#include "gaitopt/io/opensim_table.hpp"
#include "gaitopt/io/opensim_trial_file.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "import_opensim_summary.hpp"

namespace gaitopt::cli {
namespace {

// The five-link lumping of the shipped trial's person (lump-osim of its model).
constexpr const char* kDefaultPerson = "configs/robot/human_subject01.yaml";

struct ImportArgs {
  OpenSimImportFiles files;
  std::string id, out, result, window;
  std::string robot;
  std::optional<double> belt_speed;
  double cutoff_hz = 6.0;
  std::string trunk = "markers";
};

// "A:B" seconds, A < B.
std::pair<double, double> parseWindow(const std::string& text) {
  const auto colon = text.find(':');
  std::optional<double> a, b;
  if (colon != std::string::npos) a = parseDecimal(text.substr(0, colon)), b = parseDecimal(text.substr(colon + 1));
  if (!a || !b || !(*a < *b))
    throw CLI::ValidationError("--time-window", "expected START:END in seconds with START < END, got '" +
                                                    printable(text) + "'");
  return {*a, *b};
}

}  // namespace

void registerImportOpenSimCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ImportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "import-opensim",
      "Convert an OpenSim walking trial (IK .mot, GRF .mot, optional .trc markers) to the "
      "measured-data CSV at the force-plate rate. Exit 2 on bad input (nothing written).");
  cmd->add_option("--ik", args->files.ik, "OpenSim IK coordinates (.mot)")->required();
  cmd->add_option("--grf", args->files.grf, "Force-plate reactions and CoP (.mot)")->required();
  cmd->add_option("--trc", args->files.trc, "Markers (.trc): trunk line and belt speed");
  cmd->add_option("--id", args->id,
                  "OpenSim inverse dynamics (.sto): hip and knee moments checked against ours");
  cmd->add_option("--model", args->files.model,
                  "The OpenSim model (.osim) of the IK: its name and knee-flexion sign");
  cmd->add_option("--conventions", args->files.conventions,
                  "YAML mapping: plates, knee_flexion, coordinates, markers (default: detected)");
  cmd->add_option("--time-window", args->window, "Import only START:END [s]");
  cmd->add_option("--belt-speed", args->belt_speed,
                  "Treadmill belt speed [m/s] (default: estimated from the stance feet)")
      ->check(numberWithin(0.0, 10.0, true, "m/s"));
  addRobotOption(cmd, args->robot, kDefaultPerson);
  cmd->add_option("--cutoff", args->cutoff_hz,
                  "Kinematics smoothing spline: frequency of gain 1/2 [Hz]")
      ->capture_default_str()
      ->check(numberWithin(0.0, 1000.0, true, "Hz"));
  cmd->add_option("--trunk", args->trunk,
                  "Trunk line: 'markers' (pelvis to shoulders, needs --trc) or 'model' (hip to "
                  "the IK model's pelvis + torso CoM)")
      ->capture_default_str()
      ->check(CLI::IsMember({"markers", "model"}));
  CLI::Option* out = cmd->add_option("--out", args->out, "Measured-data CSV to write");
  cmd->add_option("--result", args->result,
                  "Result folder: data.csv and report.json (the point-foot analysis: torques "
                  "vs --id, force balance, alpha-row residual, rocker-foot radius)")
      ->excludes(out);
  cmd->callback([args, &exit_code]() {
    if (args->out.empty() == args->result.empty())
      throw CLI::ValidationError("--out, --result", "give one: --out DATA.csv or --result DIR");
    args->robot = robotOrDefault(args->robot, "import-opensim", kDefaultPerson);
    const RobotParams robot = loadRobot(args->robot);
    OpenSimImportOptions options;
    if (!args->window.empty()) options.time_window = parseWindow(args->window);
    OutputTransaction output({{"--ik", args->files.ik}, {"--grf", args->files.grf},
                              {"--trc", args->files.trc}, {"--id", args->id},
                              {"--robot", args->robot}, {"--model", args->files.model},
                              {"--conventions", args->files.conventions}});
    // One result, one rename: the CSV alone, or the folder holding the CSV and the report.
    const std::string dir = args->result.empty()
                                ? ""
                                : output.directory("--result", args->result,
                                                   ourFiles({"data.csv", "report.json"}));
    const std::string csv = dir.empty() ? output.file("--out", args->out) : dir + "/data.csv";
    options.belt_speed = args->belt_speed;
    options.cutoff_hz = args->cutoff_hz;
    options.trunk_from_markers = args->trunk == "markers";
    const ImportedTrial trial = importOpenSimTrial(args->files, robot, options);
    std::optional<OpenSimTable> id;
    if (!args->id.empty()) id = readOpenSimTable(args->id);
    const OpenSimAnalysis analysis = withDataErrorsAsConfigErrors(
        [&] { return analyseImportedTrial(trial, buildModel(robot), id ? &*id : nullptr); });
    printSummary(trial);
    printAnalysisAndCheck(trial, analysis, args->id);
    writeNewFile(csv, importedTrialCsv(trial));
    if (!dir.empty()) writeNewFile(dir + "/report.json", opensimAnalysisJson(analysis, trial));
    output.commit();
    exit_code = 0;
  });
}

}  // namespace gaitopt::cli
