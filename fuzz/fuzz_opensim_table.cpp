// OpenSim storage files .mot/.sto (io/opensim_table.hpp), then the column lookup that
// `import-opensim` does on them: only ConfigError (a bad file) and
// DataError (a missing column) may come out.
#include "fuzz_support.hpp"
#include "gaitopt/ident/data_error.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/opensim_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const gaitopt::OpenSimTable table =
        gaitopt::readOpenSimTable(gaitopt::fuzz::inputFile(data, size, "table.mot"));
    table.column(table.columns.back());
    table.column("pelvis_tilt");
  } catch (const gaitopt::ConfigError&) {
  } catch (const gaitopt::DataError&) {
  }
  return 0;
}
