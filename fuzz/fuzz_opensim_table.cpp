// OpenSim storage files .mot/.sto (io/opensim_table.hpp), then the column lookup that
// `import-opensim` does on them, then the file as the IK table of a recording (its inDegrees
// flag checked against its angles, io/opensim_trial_file.hpp; the shipped GRF seed beside it):
// only ConfigError (a bad file) and DataError (a missing column) may come out.
#include "fuzz_support.hpp"
#include "gaitopt/ident/data_error.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/opensim_table.hpp"
#include "gaitopt/io/opensim_trial_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const std::string path = gaitopt::fuzz::inputFile(data, size, "table.mot");
    const gaitopt::OpenSimTable table = gaitopt::readOpenSimTable(path);
    table.column(table.columns.back());
    gaitopt::readOpenSimRecording({path, GAITOPT_SOURCE_DIR "/fuzz/seeds/grf.mot", ""});
    table.column("pelvis_tilt");
  } catch (const gaitopt::ConfigError&) {
  } catch (const gaitopt::DataError&) {
  }
  return 0;
}
