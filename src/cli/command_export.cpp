// `gaitopt export`: N steps of a gait for a joint-level controller, as CSV or JSON.
#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli_common.hpp"
#include "override_options.hpp"
#include "commands.hpp"
#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/export/gait_library.hpp"
#include "gaitopt/io/output_transaction.hpp"

namespace gaitopt::cli {
namespace {


// The ramped walk's rows, or nothing (message printed) when a sample violates a constraint.
std::optional<std::vector<ExportRow>> rampedExport(const GaitEvaluator& evaluator,
                                                   const GaitParameters& p,
                                                   const GaitEvaluation<double>& e,
                                                   const Model& model, ExportRequest& req, bool stop) {
  std::vector<WalkStepMotion> walk;
  try {
    walk = rampedWalk(evaluator, p, e, {req.ramp_steps, req.ramp_steps, req.steps, stop});
  } catch (const InfeasibleRamp& error) {
    std::cerr << "gaitopt: error: --ramp: " << error.what()
              << (stop ? " (--ramp-out none exports the ramp-in alone)" : "")
              << "; nothing exported\n";
    return std::nullopt;
  }
  for (const WalkStepMotion& s : walk)
    if (s.single_support) req.ramp_rates.push_back(s.evaluation->motion.alphadot_iSS);
  const std::vector<PlannedSample> samples = sampleWalk(evaluator, walk, req.rate);
  const auto gait = std::make_shared<const GaitEvaluation<double>>(e);
  const std::vector<ConstraintMaximum> bad = violations(
      sampleConstraintMaxima(evaluator, walk, samples), gaitBaseline(evaluator, gait));
  for (const ConstraintMaximum& c : bad) {
    std::cerr << "gaitopt: error: --ramp: constraint " << c.name << " violated by "
              << shortNumber(c.value, "%.4g") << " " << c.unit << " at t = "
              << shortNumber(c.t, "%.4f") << " s (step " << c.step << ")\n";
  }
  if (!bad.empty()) return std::nullopt;
  return exportWalk(evaluator, model, walk, samples, req.first_stance);
}

struct ExportArgs {
  OverrideArgs overrides;
  std::string gait, library, out, format = "csv", first_stance = "left", ramp_out = "stop",
      rotor = "exact";
  int steps = 10, ramp_steps = 2;
  bool ramp = false;
  double rate = 1000.0;
};

RotorModel rotorOf(const std::string& name) {
  return name == "exact" ? RotorModel::Exact : RotorModel::HighGear;
}

// `--library SWEEP_DIR`: the sweep's optimal gaits in one JSON file.
void exportLibrary(const ExportArgs& args, int& exit_code) {
  if (args.format != "json" || args.ramp) {
    std::cerr << "gaitopt: error: --library writes the gaits' JSON phases: it needs --format "
                 "json and takes no --ramp\n";
    exit_code = kExitBadInput;
    return;
  }
  const std::vector<LibraryGait> gaits = loadSweepGaits(args.library);
  OutputTransaction output({{"--library", args.library}});
  writeNewFile(output.file("--out", args.out), gaitLibraryJson(gaits, rotorOf(args.rotor)));
  output.commit();
  std::cout << "export: library of " << gaits.size() << " gaits, "
            << shortNumber(gaits.front().speed) << " to " << shortNumber(gaits.back().speed)
            << " m/s, rotor " << args.rotor << " -> " << args.out << "\n";
  exit_code = 0;
}

}  // namespace

void registerExportCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Export N consecutive steps of a gait (alternating physical stance leg) at a fixed rate "
      "for a controller: phase variable, motor angles, feedforward torques split into parts, "
      "feet and planned reactions. Exit 3 if the gait is undefined, 2 on bad input.");
  CLI::Option_group* source = cmd->add_option_group("source", "--gait or --library");
  source->add_option("--gait", args->gait, "Gait YAML file")->check(CLI::ExistingFile);
  source
      ->add_option("--library", args->library,
                   "gaitopt sweep output: its optimal gaits in one JSON file (with "
                   "--format json; --steps, --rate, --first-stance, --ramp do not apply)")
      ->check(CLI::ExistingDirectory);
  source->require_option(1);
  cmd->add_option("--out", args->out, "Output file")->required();
  addOverrideOptions(cmd, args->overrides, nullptr);  // of --gait
  cmd->add_option("--steps", args->steps, "Number of steps (>= 1)")
      ->capture_default_str()
      ->check(integerWithin(1, 100000));
  cmd->add_option("--rate", args->rate, "Sample rate [Hz] (0 < HZ <= 1e5)")
      ->capture_default_str()
      ->check(numberWithin(0.0, 1e5, true, "Hz"));
  cmd->add_option("--format", args->format, "csv or json")
      ->capture_default_str()
      ->check(CLI::IsMember({"csv", "json"}));
  cmd->add_option("--first-stance", args->first_stance, "Physical stance leg of step 0")
      ->capture_default_str()
      ->check(CLI::IsMember({"left", "right"}));
  cmd->add_option("--rotor", args->rotor,
                  "Rotor model of the feedforward: exact (1.17) or high_gear (A.1), the "
                  "armature model of export-model's MJCF")
      ->capture_default_str()
      ->check(CLI::IsMember({"exact", "high_gear"}));
  cmd->add_flag("--ramp", args->ramp,
                 "Start from standing still and end standing: ramp-in and ramp-out steps "
                 "around the N cyclic steps, every sample checked against the constraints "
                 "(exit 3 if one is violated)");
  cmd->add_option("--ramp-steps", args->ramp_steps, "Steps of the ramp-in and of the ramp-out")
      ->capture_default_str()
      ->check(integerWithin(2, 1000));
  cmd->add_option("--ramp-out", args->ramp_out,
                  "stop: ramp out to standing still; none: end with the last cyclic step")
      ->capture_default_str()
      ->check(CLI::IsMember({"stop", "none"}));
  cmd->callback([args, &exit_code]() {
    if (!args->library.empty() && !(args->overrides.robot.empty() && args->overrides.set.empty()))
      throw CLI::ValidationError("--robot, --set", "override the --gait file, not a --library");
    if (!args->library.empty()) return exportLibrary(*args, exit_code);
    const GaitFile gait =
        loadGaitFileWithOverrides(args->gait, overridesOf(args->overrides, nullptr));
    // The JSON export writes each virtual constraint as one polynomial; a B-spline is piecewise.
    if (args->format == "json" && gait.options.parameterisation.basis == PathBasis::BSpline) {
      std::cerr << "gaitopt: error: " << args->gait << ": parameterisation.basis: the JSON "
                << "controller export needs 'polynomial', got 'bspline' (use --format csv)\n";
      exit_code = kExitBadInput;
      return;
    }
    OutputTransaction output({{"--gait", args->gait}});
    const std::string staged = output.file("--out", args->out);
    const GaitEvaluator evaluator(gait.robot, gait.options, gait.model_options);
    const GaitEvaluation<double> e = evaluator.evaluate(gait.parameters);
    if (!e.defined() || !e.motion_computed) {
      std::cerr << "gaitopt: error: " << args->gait << ": the step is undefined (failed level "
                << e.failed_level << "); nothing exported\n";
      exit_code = kExitUndefined;
      return;
    }
    requireSampleRows("--steps, --rate", args->steps + (args->ramp ? 2 * args->ramp_steps : 0),
                      e.motion.T_SS + e.motion.T_DS, args->rate);
    ExportRequest req;
    req.steps = args->steps;
    req.rate = args->rate;
    req.first_stance = args->first_stance == "left" ? Leg::Left : Leg::Right;
    req.rotor = rotorOf(args->rotor);
    // The feedforward overcomes the robot file's whole friction, not only the optimised part.
    ModelOptions feedforward = gait.model_options;
    feedforward.rotor = req.rotor;
    const Model model = buildModel(gait.robot, feedforward);
    req.ramp_steps = args->ramp ? args->ramp_steps : 0;
    std::vector<ExportRow> rows;
    if (args->ramp) {
      const std::optional<std::vector<ExportRow>> ramped =
          rampedExport(evaluator, gait.parameters, e, model, req, args->ramp_out == "stop");
      if (!ramped) {
        exit_code = kExitUndefined;
        return;
      }
      rows = *ramped;
    } else {
      rows = exportTrajectory(evaluator, e, model, req);
    }
    const ExportMetadata meta = exportMetadata(gait, e, req);
    writeNewFile(staged, args->format == "csv" ? exportCsv(meta, rows)
                                               : exportJson(gait, model, e, meta, rows));
    output.commit();
    const auto events = std::count_if(rows.begin(), rows.end(), [](const ExportRow& r) {
      return r.event != ExportEvent::None;
    });
    std::cout << "export: " << args->steps << " steps"
              << (args->ramp ? " + ramp of " + std::to_string(args->ramp_steps) + " in/out" : "")
              << ", " << rows.size() << " rows (" << events << " at touchdown and lift-off), "
              << shortNumber(args->rate) << " Hz, speed " << shortNumber(e.speed, "%.4g")
              << " m/s, rotor " << args->rotor << " -> " << args->out << "\n";
    exit_code = 0;
  });
}

}  // namespace gaitopt::cli
