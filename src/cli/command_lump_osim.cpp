// `gaitopt lump-osim`: a five-link robot file lumped from an OpenSim model (.osim).
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/ident/osim_lumping.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/file_digest.hpp"
#include "gaitopt/io/lumped_robot_file.hpp"
#include "gaitopt/io/opensim_trial_file.hpp"
#include "gaitopt/io/osim_model_file.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/robot_file.hpp"

namespace gaitopt::cli {
namespace {

struct LumpArgs {
  std::string model, out, name;
  std::vector<std::string> thighs{"femur_r", "femur_l"};
};

bool isPlainName(const std::string& s) {
  if (s.empty() || s.size() > 100) return false;
  for (const char c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.') return false;
  return true;
}

// The model file's stem with every character outside [A-Za-z0-9_.-] made '_'.
std::string defaultName(const std::string& model) {
  std::string stem = std::filesystem::path(model).stem().string();
  for (char& c : stem)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
  return stem.empty() ? "osim_model" : stem.substr(0, 100);
}

void printLumping(const OsimLumping& l, const std::string& out) {
  const RobotParams& r = l.robot;
  std::cout << "lump-osim: " << r.name << " -> " << out << "\n"
            << "  tibia " << shortNumber(r.mass[0], "%.3f") << " kg, l1 " << shortNumber(r.l1, "%.4f")
            << " m, s1 " << shortNumber(r.s[0], "%.4f") << " m, I1 " << shortNumber(r.inertia[0], "%.4f") << " kg m^2\n"
            << "  femur " << shortNumber(r.mass[1], "%.3f") << " kg, l2 " << shortNumber(r.l2, "%.4f")
            << " m, s2 " << shortNumber(r.s[1], "%.4f") << " m, I2 " << shortNumber(r.inertia[1], "%.4f") << " kg m^2\n"
            << "  trunk " << shortNumber(r.mass[2], "%.3f") << " kg, s3 " << shortNumber(r.s[2], "%.4f")
            << " m, I3 " << shortNumber(r.inertia[2], "%.4f") << " kg m^2\n"
            << "  total " << shortNumber(l.model_mass, "%.3f") << " kg; largest left/right difference "
            << shortNumber(100.0 * l.asymmetry, "%.2f") << " % (" << l.asymmetry_quantity << ")\n";
}

}  // namespace

void registerLumpOsimCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<LumpArgs>();
  CLI::App* cmd = app.add_subcommand(
      "lump-osim",
      "Write a five-link robot file lumped from an OpenSim model (.osim): tibia + foot, femur, "
      "pelvis + torso (+ arms, head), sagittal plane, parallel-axis theorem at zero angles.");
  cmd->add_option("--model", args->model, "OpenSim model file (.osim, OpenSim 3 or 4)")->required();
  cmd->add_option("--out", args->out, "Robot file to write (.yaml)")->required();
  cmd->add_option("--name", args->name, "Robot name (default: the model file's stem)");
  cmd->add_option("--thighs", args->thighs, "Right and left thigh bodies")
      ->delimiter(',')
      ->expected(2)
      ->capture_default_str();
  cmd->callback([args, &exit_code]() {
    const std::string name = args->name.empty() ? defaultName(args->model) : args->name;
    if (!isPlainName(name))
      throw CLI::ValidationError("--name", "'" + printable(name) + "': use letters, digits, '_', '-' and '.' (1 to 100)");
    const OsimModel model = loadOsimModel(args->model);
    OsimLumping lumping = withDataErrorsAsConfigErrors([&] {
      return lumpOsimModel(model, {args->thighs[0], args->thighs[1]});
    });
    lumping.robot.name = name;
    const std::string yaml =
        lumpedRobotYaml(lumping, name, printable(args->model, 400), fileSha256(args->model));
    parseRobot(YAML::Load(yaml), args->out);  // what is written must read back as a robot
    OutputTransaction output({{"--model", args->model}});
    writeNewFile(output.file("--out", args->out), yaml);
    output.commit();
    printLumping(lumping, args->out);
    exit_code = 0;
  });
}

}  // namespace gaitopt::cli
