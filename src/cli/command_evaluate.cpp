// `gaitopt evaluate`: one walking step from a gait file → summary.json (+ trajectory.csv).
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli_common.hpp"
#include "override_options.hpp"
#include "commands.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/feasibility.hpp"
#include "gaitopt/gait/constraint_summary.hpp"
#include "gaitopt/io/summary_file.hpp"
#include "gaitopt/io/trajectory_file.hpp"
#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/io/gait_file.hpp"

namespace gaitopt::cli {
namespace {

namespace fs = std::filesystem;

struct EvaluateArgs {
  std::string gait, out;
  OverrideArgs overrides;
  std::optional<double> sample_rate;
};

}  // namespace

void registerEvaluateCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<EvaluateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "evaluate",
      "Evaluate one walking step of a gait file: writes OUT/summary.json and, for a defined "
      "step, OUT/trajectory.csv. Exit 0: step defined (level-5 constraints may be violated); "
      "3: step undefined (summary.json still written); 2: bad input (nothing written).");
  cmd->add_option("--gait", args->gait, "Gait YAML file (robot, parameters, options)")
      ->required();
  cmd->add_option("--out", args->out, "Output directory (created if missing)")->required();
  addOverrideOptions(cmd, args->overrides, "options.target_speed");
  cmd->add_option("--sample-rate", args->sample_rate,
                  "trajectory.csv sample rate [Hz], overrides options.sample_rate (0 < HZ <= 1e5)")
      ->check(numberWithin(0.0, 1e5, true, "Hz"));
  cmd->callback([args, &exit_code]() {
    // Everything that can fail on bad input happens before the output directory is touched.
    GaitFile gait =
        loadGaitFileWithOverrides(args->gait, overridesOf(args->overrides, "options.target_speed"));
    if (args->sample_rate) gait.options.sample_rate = *args->sample_rate;
    OutputTransaction output({{"--gait", args->gait}});
    const fs::path dir = output.directory("--out", args->out, ourOutputs());  // before any work

    const GaitEvaluator evaluator(gait.robot, gait.options, gait.model_options);
    const GaitEvaluation<double> e = evaluator.evaluate(gait.parameters);
    const bool defined = e.defined();
    const std::string summary = gaitSummaryJson(evaluator, gait.parameters, e, [&](JsonWriter& w) {
      writeOverridesJson(w, gait.overrides);
    });
    std::optional<std::string> csv;
    if (defined && e.motion_computed) {
      csv = trajectoryCsv(sampleTrajectory(evaluator, e, gait.options.sample_rate));
    }

    writeNewFile((dir / "summary.json").string(), summary);
    if (csv) writeNewFile((dir / "trajectory.csv").string(), *csv);
    output.commit();

    const bool criteria = defined && e.motion_computed;
    const FeasibilityVerdict verdict = feasibilityVerdict(evaluator, gait.parameters, e);
    std::string unmet;
    for (const std::string& g : verdict.unmet_groups) unmet += (unmet.empty() ? "" : ", ") + g;
    // One vocabulary with optimize and sweep: feasible, infeasible (some constraint unmet, the
    // step computed), undefined (a level 0-4 constraint fails: no motion).
    std::cout << "evaluate: "
              << (!defined ? "undefined, failed level " + std::to_string(verdict.failed_level)
                  : verdict.feasible ? std::string("feasible")
                                     : "infeasible, unmet level " +
                                           std::to_string(verdict.failed_level) + " (" + unmet +
                                           ")")
              << ", C_Gamma " << (criteria ? shortNumber(e.C_Gamma) + " N^2 m s" : "n/a")
              << ", speed "
              << (zeroDynamicsComputed(evaluator, e) ? shortNumber(e.speed, "%.4g") + " m/s"
                                                     : std::string("n/a"))
              << ", largest violation at the nodes " << shortNumber(maxDefinedViolation(e), "%.4g")
              << ", between them (10x) "
              << (verdict.between_nodes.worst_group < 0
                      ? std::string("n/a")
                      : shortNumber(verdict.between_nodes.worst_scaled, "%.3g") + " scaled")
              << " -> "
              << args->out << "\n";
    const std::string friction = robotFrictionMessage(evaluator.layout(), verdict.robot_friction);
    if (!friction.empty()) std::cerr << "gaitopt: evaluate: " << friction << "\n";
    exit_code = defined ? 0 : kExitUndefined;
  });
}

}  // namespace gaitopt::cli
