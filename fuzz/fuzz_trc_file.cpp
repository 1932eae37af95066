// Motion-capture marker files .trc (io/trc_file.hpp), then the marker lookup that
// `import-opensim` does on them: only ConfigError (a bad file) and
// DataError (a missing marker) may come out.
#include "fuzz_support.hpp"
#include "gaitopt/ident/data_error.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/trc_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const gaitopt::TrcData trc = gaitopt::readTrcFile(gaitopt::fuzz::inputFile(data, size, "markers.trc"));
    if (!trc.markers.empty()) trc.marker(trc.markers.back());
    trc.marker("R.Heel");
  } catch (const gaitopt::ConfigError&) {
  } catch (const gaitopt::DataError&) {
  }
  return 0;
}
