// Measured-data CSV files (io/measured_data.hpp), as read by `gaitopt identify`, `diagnose` and
// written by `import-opensim`: only ConfigError may come out.
#include "fuzz_support.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/measured_data.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    gaitopt::readMeasuredCsv(gaitopt::fuzz::inputFile(data, size, "measured.csv"));
  } catch (const gaitopt::ConfigError&) {
  }
  return 0;
}
