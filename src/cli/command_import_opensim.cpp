// `gaitopt import-opensim`: OpenSim IK + GRF (+ markers) → measured-data CSV at the GRF rate,
// optionally with the point-foot analysis of the trial as JSON.
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/opensim_analysis_file.hpp"
#include "gaitopt/io/opensim_table.hpp"
#include "gaitopt/io/opensim_trial_file.hpp"
#include "gaitopt/io/robot_file.hpp"

namespace gaitopt::cli {
namespace {

struct ImportArgs {
  OpenSimImportFiles files;
  std::string id, out, report;
  std::string robot = "configs/robot/human_subject01.yaml";
  std::optional<double> belt_speed;
  double cutoff_hz = 6.0;
  std::string trunk = "markers";
};

void printSummary(const ImportedTrial& trial) {
  std::cout << "belt speed " << shortNumber(trial.belt_speed, "%.4f") << " m/s ("
            << trial.belt_source << "), trunk line from " << trial.trunk_source << "\n";
  if (trial.belt_source == "IK ankle") {
    std::cout << "  note: the IK ankle creeps forward in stance (about 0.1 m/s on the shipped trial);"
                 " give --trc or --belt-speed for a better estimate\n";
  }
  for (const GaitEvent& e : trial.events) {
    std::cout << "  " << shortNumber(e.time, "%.4f") << " s  " << sideName(e.side) << ' '
              << (e.heel_strike ? "heel strike" : "toe off") << "\n";
  }
  std::cout << trial.t.size() << " samples, " << trial.step.back() + 1 << " steps\n";
}

void printAnalysis(const OpenSimAnalysis& a) {
  for (const JointComparison& j : a.joints) {
    std::cout << j.joint << ": RMS difference to OpenSim " << shortNumber(j.rms, "%.2f")
              << " N m (reference RMS " << shortNumber(j.reference_rms, "%.2f")
              << "), correlation " << shortNumber(j.correlation, "%.3f") << "\n";
  }
  std::cout << "single-support alpha-row residual RMS " << shortNumber(a.alpha_residual_rms, "%.2f")
            << " N m, measured CoP moment RMS " << shortNumber(a.cop_moment_rms, "%.2f")
            << " N m, correlation " << shortNumber(a.alpha_cop_correlation, "%.3f")
            << "; left unexplained with the measured CoP " << shortNumber(a.alpha_minus_cop_rms, "%.2f")
            << " N m, with a rocker foot " << shortNumber(a.alpha_minus_rocker_rms, "%.2f") << " N m\n";
  std::cout << "rocker radius " << shortNumber(a.rocker.radius_all, "%.3f") << " m = "
            << shortNumber(a.rocker.radius_all / a.rocker.leg_length, "%.3f")
            << " x leg length (literature ~0.3); held-out CoP RMS point foot "
            << shortNumber(a.rocker.holdout_rms_point, "%.4f") << " m, rocker "
            << shortNumber(a.rocker.holdout_rms_rocker, "%.4f") << " m\n";
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
  cmd->add_option("--id", args->id, "OpenSim inverse dynamics (.sto): torques compared in --report");
  cmd->add_option("--belt-speed", args->belt_speed,
                  "Treadmill belt speed [m/s] (default: estimated from the stance feet)")
      ->check(numberWithin(0.0, 10.0, true, "m/s"));
  cmd->add_option("--robot", args->robot, "Five-link lumped robot file (lengths, masses)")
      ->capture_default_str();
  cmd->add_option("--cutoff", args->cutoff_hz,
                  "Kinematics smoothing spline: frequency of gain 1/2 [Hz]")
      ->capture_default_str()
      ->check(numberWithin(0.0, 1000.0, true, "Hz"));
  cmd->add_option("--trunk", args->trunk,
                  "Trunk line: 'markers' (pelvis to shoulders, needs --trc) or 'model' (hip to "
                  "the IK model's pelvis + torso CoM)")
      ->capture_default_str()
      ->check(CLI::IsMember({"markers", "model"}));
  cmd->add_option("--out", args->out, "Measured-data CSV to write")->required();
  cmd->add_option("--report", args->report,
                  "Also write the point-foot analysis (inverse dynamics vs --id, alpha-row "
                  "residual, rocker-foot radius) as JSON");
  cmd->callback([args, &exit_code]() {
    const RobotParams robot = loadRobot(args->robot);
    OutputTransaction output({{"--ik", args->files.ik}, {"--grf", args->files.grf},
                              {"--trc", args->files.trc}, {"--id", args->id},
                              {"--robot", args->robot}});
    const std::string csv = output.file("--out", args->out);
    const std::string report = args->report.empty() ? "" : output.file("--report", args->report);
    OpenSimImportOptions options;
    options.belt_speed = args->belt_speed;
    options.cutoff_hz = args->cutoff_hz;
    options.trunk_from_markers = args->trunk == "markers";
    const ImportedTrial trial = importOpenSimTrial(args->files, robot, options);
    std::optional<OpenSimTable> id;
    if (!args->id.empty()) id = readOpenSimTable(args->id);
    std::optional<OpenSimAnalysis> analysis;
    if (!args->report.empty())
      analysis = withDataErrorsAsConfigErrors(
          [&] { return analyseImportedTrial(trial, buildModel(robot), id ? &*id : nullptr); });
    printSummary(trial);
    writeNewFile(csv, importedTrialCsv(trial));
    if (analysis) {
      printAnalysis(*analysis);
      writeNewFile(report, opensimAnalysisJson(*analysis));
    }
    output.commit();
    exit_code = 0;
  });
}

}  // namespace gaitopt::cli
