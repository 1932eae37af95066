// Optimiser configuration files (io/optimize_config.hpp), including their Ipopt options and the
// robot and initial-guess files they name: only ConfigError may come out.
#include "fuzz_support.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/optimize_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    gaitopt::loadOptimizeConfig(gaitopt::fuzz::inputFile(data, size, "config_input.yaml"));
  } catch (const gaitopt::ConfigError&) {
  }
  return 0;
}
