// `gaitopt synth`: synthetic measured walking data from a TRUE model (robot + named effects).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/ident/admissible_range.hpp"
#include "gaitopt/ident/synth.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/measured_data.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "gaitopt/io/synth_truth_file.hpp"

namespace gaitopt::cli {
namespace {

struct SynthArgs {
  std::string robot, gait, out, noise = "default";
  std::vector<std::string> effects, unmodelled;
  SynthOptions options;
};

// The VALUE of a spec in the one number syntax of the command line (the spec parsers take any
// stod).
void requireDecimalValue(const char* option, const std::string& spec) {
  const std::size_t eq = spec.find('=');
  if (eq != std::string::npos && !parseDecimal(spec.substr(eq + 1)))
    throw CLI::ValidationError(option, "'" + printable(spec) + "': " +
                                           decimalProblem(spec.substr(eq + 1)));
}

// A value beyond what synth generates on the robot (ident/admissible_range.hpp) is refused.
void requireWithin(const char* option, const std::string& spec, double value,
                   const AdmissibleRange& range, const std::string& unit) {
  if (!range.containsClosed(value))
    throw CLI::ValidationError(option, "'" + printable(spec) + "': outside the range synth "
                                       "generates on the robot, [" + shortNumber(range.lo) +
                                       ", " + shortNumber(range.hi) + "] " + unit + ": " +
                                       range.basis);
}

}  // namespace

void registerSynthCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SynthArgs>();
  CLI::App* cmd = app.add_subcommand(
      "synth",
      "Synthesise measured walking data (CSV for `gaitopt diagnose`) from the robot plus hidden "
      "effects; writes FILE with the hidden truth (JSON) as its '#' comment lines. Exit 2: bad input; 3: the TRUE model cannot "
      "walk the gait.");
  cmd->add_option("--robot", args->robot, "Nominal robot YAML file")->required();
  cmd->add_option("--gait", args->gait, "Gait YAML file (its parameters and options)")->required();
  cmd->add_option("--steps", args->options.steps, "Number of steps, 3 to 300 (a file diagnose reads: 10^5 samples)")
      ->required()
      ->check(integerWithin(3, 300));
  cmd->add_option("--effect", args->effects,
                  "Hidden effect NAME[@JOINT]=VALUE (repeatable), e.g. coulomb@knee_right=3.2");
  cmd->add_option("--unmodelled", args->unmodelled,
                  "Effect outside diagnose's library NAME@JOINT=VALUE (repeatable): "
                  "knee_centre@KNEE=m/rad, joint_compliance@JOINT=N·m/rad, ground_compliance=N/m");
  cmd->add_option("--noise", args->noise, "default (2^14 counts/rev, 0.3 N·m, 2 N) or none")
      ->check(CLI::IsMember({"default", "none"}));
  cmd->add_option("--seed", args->options.seed,
                  "Random seed (gait variation and noise), 0 to 2^53-1")
      ->check(integerWithin(0, (std::int64_t{1} << 53) - 1));
  cmd->add_option("--out", args->out, "Output CSV file")->required();
  cmd->callback([args, &exit_code]() {
    const RobotParams robot = loadRobot(args->robot);
    std::vector<Effect> effects;
    for (const std::string& spec : args->effects) {
      requireDecimalValue("--effect", spec);
      try {
        effects.push_back(parseEffectSpec(spec));
      } catch (const std::invalid_argument& e) {
        throw CLI::ValidationError("--effect", "'" + printable(spec) + "': " + e.what());
      }
      const Effect& e = effects.back();
      requireWithin("--effect", spec, e.value, synthesisRange(e, robot), effectInfo(e.kind).unit);
    }
    for (const std::string& spec : args->unmodelled) {
      requireDecimalValue("--unmodelled", spec);
      try {
        args->options.unmodelled.push_back(parseUnmodelledSpec(spec));
      } catch (const std::invalid_argument& e) {
        throw CLI::ValidationError("--unmodelled", "'" + printable(spec) + "': " + e.what());
      }
      const UnmodelledEffect& e = args->options.unmodelled.back();
      requireWithin("--unmodelled", spec, e.value, unmodelledRange(e, robot),
                    unmodelledUnit(e.kind));
    }
    const GaitFile gait = loadGaitFile(args->gait);
    args->options.noise = args->noise == "default";
    OutputTransaction output({{"--robot", args->robot}, {"--gait", args->gait}});
    const std::string csv = output.file("--out", args->out);
    MeasuredData data;
    try {
      data = synthesize(robot, gait.parameters, gait.options, gait.model_options, effects,
                        args->options);
    } catch (const std::runtime_error& e) {
      std::cerr << "gaitopt: " << e.what() << "\n";
      exit_code = kExitUndefined;
      return;
    }
    writeNewFile(csv, measuredCsv(data, synthTruthJson(args->robot, args->gait, effects,
                                                      args->options)));
    output.commit();
    std::cout << "synth: " << args->options.steps << " steps, " << data.size() << " samples, "
              << effects.size() << " effect(s) -> " << args->out << "\n";
    exit_code = 0;
  });
}

}  // namespace gaitopt::cli
