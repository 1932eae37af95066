// Robot description files (io/robot_file.hpp), parsed from memory with the checks of
// loadYamlFile: only ConfigError may come out.
#include <string>

#include "fuzz_support.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "gaitopt/io/yaml_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    gaitopt::parseRobot(gaitopt::parseYamlText(text, "robot.yaml"), "robot.yaml");
  } catch (const gaitopt::ConfigError&) {
  }
  return 0;
}
