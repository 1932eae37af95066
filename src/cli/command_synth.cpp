// `gaitopt synth`: synthetic measured walking data from a TRUE model (robot + named effects).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/ident/synth.hpp"
#include "gaitopt/io/atomic_file.hpp"
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

}  // namespace

void registerSynthCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SynthArgs>();
  CLI::App* cmd = app.add_subcommand(
      "synth",
      "Synthesise measured walking data (CSV for `gaitopt diagnose`) from the robot plus hidden "
      "effects; writes FILE and FILE.truth.json. Exit 2: bad input; 3: the TRUE model cannot "
      "walk the gait.");
  cmd->add_option("--robot", args->robot, "Nominal robot YAML file")->required();
  cmd->add_option("--gait", args->gait, "Gait YAML file (its parameters and options)")->required();
  cmd->add_option("--steps", args->options.steps, "Number of steps (>= 3)")
      ->required()
      ->check(CLI::Range(3, 100000));
  cmd->add_option("--effect", args->effects,
                  "Hidden effect NAME[@JOINT]=VALUE (repeatable), e.g. coulomb@knee_right=3.2");
  cmd->add_option("--unmodelled", args->unmodelled,
                  "Effect outside diagnose's library NAME@JOINT=VALUE (repeatable): "
                  "knee_centre@KNEE=m/rad, joint_compliance@JOINT=N·m/rad");
  cmd->add_option("--noise", args->noise, "default (2^14 counts/rev, 0.3 N·m, 2 N) or none")
      ->check(CLI::IsMember({"default", "none"}));
  cmd->add_option("--seed", args->options.seed, "Random seed (gait variation and noise)");
  cmd->add_option("--out", args->out, "Output CSV file")->required();
  cmd->callback([args, &exit_code]() {
    std::vector<Effect> effects;
    for (const std::string& spec : args->effects) {
      try {
        effects.push_back(parseEffectSpec(spec));
      } catch (const std::invalid_argument& e) {
        throw CLI::ValidationError("--effect", "'" + spec + "': " + e.what());
      }
    }
    for (const std::string& spec : args->unmodelled) {
      try {
        args->options.unmodelled.push_back(parseUnmodelledSpec(spec));
      } catch (const std::invalid_argument& e) {
        throw CLI::ValidationError("--unmodelled", "'" + spec + "': " + e.what());
      }
    }
    const RobotParams robot = loadRobot(args->robot);
    const GaitFile gait = loadGaitFile(args->gait);
    args->options.noise = args->noise == "default";
    MeasuredData data;
    try {
      data = synthesize(robot, gait.parameters, gait.options, gait.model_options, effects,
                        args->options);
    } catch (const std::runtime_error& e) {
      std::cerr << "gaitopt: " << e.what() << "\n";
      exit_code = kExitUndefined;
      return;
    }
    writeFileAtomically(args->out, measuredCsv(data));
    writeFileAtomically(args->out + ".truth.json",
                        synthTruthJson(args->robot, args->gait, effects, args->options));
    std::cout << "synth: " << args->options.steps << " steps, " << data.size() << " samples, "
              << effects.size() << " effect(s) -> " << args->out << "\n";
    exit_code = 0;
  });
}

}  // namespace gaitopt::cli
