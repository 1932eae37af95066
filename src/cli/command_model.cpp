// `gaitopt model`: model terms at one state, as JSON on standard output.
#include <iostream>

#include "cli_common.hpp"
#include "data_files.hpp"
#include "commands.hpp"
#include "gaitopt/io/model_report.hpp"
#include "gaitopt/io/robot_file.hpp"

namespace gaitopt::cli {
namespace {

// Documented ranges of the state (docs/commands/model.md): angles of a few turns, rates and
// accelerations far beyond any gait; beyond them the model terms overflow or mean nothing.
constexpr double kMaxAngle = 100.0;          // rad
constexpr double kMaxRate = 1e3;             // rad/s
constexpr double kMaxAcceleration = 1e5;     // rad/s^2

struct ModelArgs {
  std::string robot;  // empty: the default robot (data_files.hpp)
  std::vector<double> q, qd, qdd;
  std::string rotor = "exact";
};

Vec5 toVec5(const std::vector<double>& v) {
  return v.empty() ? Vec5::Zero() : Vec5(Eigen::Map<const Vec5>(v.data()));
}

}  // namespace

void registerModelCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ModelArgs>();
  CLI::App* cmd = app.add_subcommand(
      "model", "Print the pinned (5-DOF) and floating (7-DOF) model terms at one state as JSON.");
  addRobotOption(cmd, args->robot);
  cmd->add_option("--q", args->q, "Configuration alpha,delta1,delta2,delta3,delta4 [rad]")
      ->required()
      ->delimiter(',')
      ->expected(5)
      ->check(numberWithin(-kMaxAngle, kMaxAngle, false, "rad"));
  cmd->add_option("--qd", args->qd, "Velocities [rad/s], 5 comma-separated values (default 0)")
      ->delimiter(',')
      ->expected(5)
      ->check(numberWithin(-kMaxRate, kMaxRate, false, "rad/s"));
  cmd->add_option("--qdd", args->qdd,
                  "Accelerations [rad/s^2], 5 values; adds single-support inverse dynamics")
      ->delimiter(',')
      ->expected(5)
      ->check(numberWithin(-kMaxAcceleration, kMaxAcceleration, false, "rad/s^2"));
  cmd->add_option("--rotor", args->rotor,
                  "Rotor kinetic energy: 'exact' (1.17) or 'high_gear' (Appendix A, A.1)")
      ->capture_default_str()
      ->check(CLI::IsMember({"exact", "high_gear"}));
  cmd->callback([args, &exit_code]() {
    ModelOptions options;
    options.rotor = args->rotor == "exact" ? RotorModel::Exact : RotorModel::HighGear;
    const Model model = buildModel(loadRobot(robotOrDefault(args->robot, "model")), options);
    std::optional<Vec5> qdd;
    if (!args->qdd.empty()) qdd = toVec5(args->qdd);
    std::cout << modelReportJson(model, toVec5(args->q), toVec5(args->qd), qdd);
    exit_code = 0;
  });
}

}  // namespace gaitopt::cli
