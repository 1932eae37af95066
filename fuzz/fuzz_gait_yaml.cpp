// Gait files (io/gait_file.hpp), robot references resolved in the harness' copy of configs/:
// only ConfigError may come out.
#include "fuzz_support.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/gait_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    gaitopt::loadGaitFile(gaitopt::fuzz::inputFile(data, size, "gait/gait_input.yaml"));
  } catch (const gaitopt::ConfigError&) {
  }
  return 0;
}
