// Uses the installed library (the default robot's model from the installed data) and the
// walker's C interface (a load error that names the file).
#include <cstdio>
#include <gaitopt/control/walker.h>
#include <gaitopt/io/robot_file.hpp>
#include <gaitopt/model/model.hpp>

int main() {
  const gaitopt::Model m = gaitopt::buildModel(
      gaitopt::loadRobot(std::string(GAITOPT_DATA_DIR) + "/configs/robot/rabbit_miossec.yaml"));
  char error[512] = "";
  gaitopt_walker* w = gaitopt_walker_load("absent.json", nullptr, error, sizeof error);
  std::printf("robot %s mass %.15g\nwalker %s: %s\n", m.robot.name.c_str(), m.total_mass,
              w ? "loaded" : "refused", error);
  return w == nullptr ? 0 : 1;
}
