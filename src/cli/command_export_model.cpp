// `gaitopt export-model`: the robot as MuJoCo MJCF or URDF.
#include <iostream>
#include <memory>
#include <string>

#include "cli_common.hpp"
#include "data_files.hpp"
#include "commands.hpp"
#include "gaitopt/export/robot_export.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/robot_file.hpp"

namespace gaitopt::cli {
namespace {

struct ExportModelArgs {
  std::string robot;  // empty: the default robot (data_files.hpp)
  std::string format, out;
  ModelExportOptions options;
};

}  // namespace

void registerExportModelCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ExportModelArgs>();
  CLI::App* cmd = app.add_subcommand(
      "export-model",
      "Write the robot as MuJoCo MJCF or URDF (planar floating base, support bar as a point "
      "mass at the hip, point feet as small spheres, rotor inertia as MJCF armature).");
  addRobotOption(cmd, args->robot);
  cmd->add_option("--format", args->format, "mjcf or urdf")
      ->required()
      ->check(CLI::IsMember({"mjcf", "urdf"}));
  cmd->add_option("--out", args->out, "Output file")->required();
  cmd->add_option("--foot-radius", args->options.foot_radius, "Foot sphere radius [m]")
      ->capture_default_str()
      ->check(numberWithin(1e-4, 0.1, false, "m"));
  cmd->add_option("--ground-friction", args->options.ground_friction,
                  "MJCF sliding friction of feet on the floor")
      ->capture_default_str()
      ->check(numberWithin(0.0, 10.0));
  cmd->add_option("--timestep", args->options.timestep, "MJCF simulation time step [s]")
      ->capture_default_str()
      ->check(numberWithin(1e-6, 0.01, false, "s"));
  cmd->callback([args, &exit_code]() {
    const std::string robot_path = robotOrDefault(args->robot, "export-model");
    const RobotParams robot = loadRobot(robot_path);
    OutputTransaction output({{"--robot", robot_path}});
    writeNewFile(output.file("--out", args->out), args->format == "mjcf"
                                                      ? robotMjcf(robot, args->options)
                                                      : robotUrdf(robot, args->options));
    output.commit();
    std::cout << "export-model: " << robot.name << " as " << args->format << " -> " << args->out
              << "\n";
    exit_code = 0;
  });
}

}  // namespace gaitopt::cli
