// `gaitopt simulate`: closed-loop hybrid walking of a gait in gaitopt's own model.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "gaitopt/io/simulation_report.hpp"
#include "gaitopt/sim/cycle_convergence.hpp"
#include "gaitopt/sim/impact_touchdown.hpp"
#include "gaitopt/sim/walk_frames.hpp"

namespace gaitopt::cli {
namespace {

namespace fs = std::filesystem;

struct SimulateArgs {
  std::string gait, out, plant, impact = "auto", ds_control = "cubic";
  int steps = 20;
  double bandwidth = 40.0, gain_scale = 1.0, sample_rate = 200.0, ground_mu = -1.0;
  bool no_torque_limits = false;
  std::vector<std::string> perturb;
};

// KIND=VALUE: alphad [rad/s] or alpha, delta1..delta4 [rad], added at the first SS start.
void applyPerturbation(const std::string& text, WalkRequest& req) {
  const std::size_t eq = text.find('=');
  static const std::map<std::string, int> coordinate{
      {"alpha", 0}, {"delta1", 1}, {"delta2", 2}, {"delta3", 3}, {"delta4", 4}};
  const std::optional<double> parsed =
      eq == std::string::npos ? std::nullopt : parseDecimal(text.substr(eq + 1));
  if (!parsed)
    throw CLI::ValidationError("--perturb", "expected KIND=VALUE (a decimal VALUE), got '" +
                                                printable(text) + "'");
  const double v = *parsed;
  const std::string kind = text.substr(0, eq);
  // A perturbation the closed loop could recover from at all: a few rad/s of α̇, a fraction of
  // a radian of a coordinate (larger ones only say the robot falls, after minutes of CVODE).
  const double limit = kind == "alphad" ? 5.0 : 0.5;
  if ((kind == "alphad" || coordinate.count(kind)) && std::abs(v) > limit)
    throw CLI::ValidationError("--perturb", printable(kind) + " must be within [-" +
                                                shortNumber(limit) + ", " + shortNumber(limit) +
                                                "] " + (kind == "alphad" ? "rad/s" : "rad") +
                                                ", got '" + printable(text) + "'");
  if (kind == "alphad") {
    req.dalphad0 += v;
  } else if (kind == "slope") {
    if (std::abs(req.ground_slope + v) >= 0.5)
      throw CLI::ValidationError("--perturb", "slope must be within (-0.5, 0.5) rad, got '" +
                                                  printable(text) + "'");
    req.ground_slope += v;
  } else if (coordinate.count(kind)) {
    req.dq0(coordinate.at(kind)) += v;
  } else {
    throw CLI::ValidationError("--perturb", "unknown KIND '" + kind +
                                                "' (alphad, slope, alpha, delta1, delta2, delta3, delta4)");
  }
}

// The walk's samples as export rows (world frame, physical joints, torque parts on the plant).
std::vector<ExportRow> exportRows(const Model& plant, const WalkResult& r) {
  std::vector<ExportRow> rows;
  for (const WalkFrame& f : walkFrames(plant, r))
    rows.push_back(exportRow(plant, f.row, f.step, f.first_leg_stance ? Leg::Left : Leg::Right,
                             f.foot1_x, f.row.t));
  return rows;
}

}  // namespace

void registerSimulateCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Closed-loop hybrid walking of a gait in gaitopt's model (CVODE, events by root finding, "
      "thesis 4.3.1 controller with alpha replacing time). Writes OUT/summary.json, "
      "steps.csv, trajectory.csv, tracking.csv. Exit 0: every step walked; 3: it did not.");
  cmd->add_option("--gait", args->gait, "Gait YAML file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "Output directory (created if missing)")->required();
  cmd->add_option("--steps", args->steps, "Number of steps")
      ->capture_default_str()
      ->check(integerWithin(1, 10000));
  cmd->add_option("--perturb", args->perturb,
                  "KIND=VALUE added at the first SS start: alphad [rad/s] (on the virtual "
                  "constraints) or alpha, delta1..delta4 [rad]; slope [rad]: the ground ahead "
                  "of the first stance foot inclined, + uphill; repeatable");
  cmd->add_option("--plant", args->plant,
                  "Robot file of the simulated robot (default: the gait's robot)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--bandwidth", args->bandwidth, "Output bandwidth omega [rad/s]")
      ->capture_default_str()
      ->check(numberWithin(0.1, 1000.0, false, "rad/s"));
  cmd->add_option("--gain-scale", args->gain_scale,
                  "Scales both output gains (the walker's gain_scale, docs/walking_controller.md)")
      ->capture_default_str()
      ->check(numberWithin(0.01, 100.0));
  cmd->add_option("--sample-rate", args->sample_rate, "trajectory rows [Hz]")
      ->capture_default_str()
      ->check(numberWithin(1.0, 1e5, false, "Hz"));
  cmd->add_option("--impact", args->impact,
                  "Touchdown model: auto (double_support for a zero-velocity landing with DS, "
                  "none without DS, algebraic for an impact landing), none (impulse-free only), "
                  "double_support (plastic impact, both feet held), algebraic, differential")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "none", "double_support", "algebraic", "differential"}));
  addDsControlOption(cmd, args->ds_control);
  cmd->add_option("--ground-mu", args->ground_mu,
                  "Friction coefficient of the plant's ground (slip checks, impacts); default: "
                  "the gait's friction_coefficient")
      ->check(numberWithin(0.0, 100.0));
  cmd->add_flag("--no-torque-limits", args->no_torque_limits,
                "Do not project the inputs on the torque envelope and contact constraints");
  cmd->callback([args, &exit_code]() {
    const GaitFile gait = loadGaitFile(args->gait);
    WalkRequest req;
    for (const std::string& p : args->perturb) applyPerturbation(p, req);
    req.steps = args->steps;
    req.bandwidth = args->bandwidth;
    req.gain_scale = args->gain_scale;
    req.sample_rate = args->sample_rate;
    configureForGait(gait.options, req);
    if (args->ground_mu >= 0.0) req.plant_friction_coefficient = args->ground_mu;
    req.torque_limits = !args->no_torque_limits;
    req.ds_control = dsAlphaControlOf(args->ds_control);
    const Model controller = buildModel(gait.robot, gait.model_options);
    const Model plant =
        args->plant.empty() ? controller : buildModel(loadRobot(args->plant), gait.model_options);
    OutputTransaction output({{"--gait", args->gait}, {"--plant", args->plant}});
    const fs::path dir = output.directory(
        "--out", args->out, ourFiles({"summary.json", "steps.csv", "trajectory.csv", "tracking.csv"}));
    const GaitEvaluator evaluator(gait.robot, gait.options, gait.model_options);
    const GaitEvaluation<double> e = evaluator.evaluate(gait.parameters);
    if (!e.defined() || !e.motion_computed) {
      std::cerr << "gaitopt: error: " << args->gait << ": the step is undefined\n";
      exit_code = kExitUndefined;
      return;
    }
    requireSampleRows("--steps, --sample-rate", args->steps, e.motion.T_SS + e.motion.T_DS,
                      args->sample_rate);
    const WalkResult r = simulateWalk(
        e, controller, plant, req,
        gaitTouchdown(gait.options, args->impact, req.plant_friction_coefficient));
    ExportRequest meta_req;
    meta_req.steps = args->steps;
    meta_req.rate = args->sample_rate;
    const SimulationRun run{args->gait, args->plant, resolvedImpactModel(gait.options, args->impact),
                            req, e.motion.alphadot_iSS};
    writeNewFile((dir / "summary.json").string(), simulationSummaryJson(r, run));
    writeNewFile((dir / "steps.csv").string(), walkStepsCsv(r));
    writeNewFile((dir / "trajectory.csv").string(),
                 exportCsv(exportMetadata(gait, e, meta_req), exportRows(plant, r)));
    writeNewFile((dir / "tracking.csv").string(),
                 walkTrackingCsv(r, gait.options.friction_coefficient));
    output.commit();
    std::cout << "simulate: " << outcomeName(r.outcome)
              << (r.message.empty() ? "" : " (" + r.message + ")") << ", "
              << r.steps.size() << " steps, converged "
              << (convergedToCycle(r, run.cycle_alphad_start) ? "yes" : "no")
              << ", tracks reference "
              << (tracksReference(r, run.cycle_alphad_start) ? "yes" : "no") << " -> "
              << args->out << "\n";
    exit_code = r.outcome == WalkOutcome::Completed ? 0 : kExitUndefined;
  });
}

}  // namespace gaitopt::cli
