#include "gaitopt/ident/data_error.hpp"

#include <utility>

namespace gaitopt {

DataError::DataError(std::string file, std::string key, int line, const std::string& problem)
    : std::runtime_error(key.empty() ? problem : "key '" + key + "': " + problem),
      file_(std::move(file)),
      key_(std::move(key)),
      line_(line),
      problem_(problem) {}

}  // namespace gaitopt
