// Robot description files (io/robot_file.hpp): only ConfigError may come out.
#include "fuzz_support.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/robot_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    gaitopt::loadRobot(gaitopt::fuzz::inputFile(data, size, "robot_input.yaml"));
  } catch (const gaitopt::ConfigError&) {
  }
  return 0;
}
