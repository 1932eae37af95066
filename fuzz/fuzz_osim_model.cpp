// OpenSim models .osim (io/xml_document.hpp, io/osim_model_file.hpp), then the five-link
// lumping that `lump-osim` does on them: only ConfigError (a bad file) and DataError (a model
// that cannot be lumped) may come out.
#include "fuzz_support.hpp"
#include "gaitopt/ident/data_error.hpp"
#include "gaitopt/ident/osim_lumping.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/osim_model_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const gaitopt::OsimModel model = gaitopt::loadOsimModel(gaitopt::fuzz::inputFile(data, size, "model.osim"));
    gaitopt::lumpOsimModel(model);
  } catch (const gaitopt::ConfigError&) {
  } catch (const gaitopt::DataError&) {
  }
  return 0;
}
