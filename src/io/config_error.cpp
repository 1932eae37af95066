#include "gaitopt/io/config_error.hpp"

#include <utility>

namespace gaitopt {

namespace {

std::string formatMessage(const std::string& file, const std::string& key, int line,
                          const std::string& problem) {
  std::string message = file;
  if (line > 0) message += ":" + std::to_string(line);
  message += ": ";
  if (!key.empty()) message += "key '" + key + "': ";
  return message + problem;
}

}  // namespace

ConfigError::ConfigError(std::string file, std::string key, int line, const std::string& problem)
    : std::runtime_error(formatMessage(file, key, line, problem)),
      file_(std::move(file)),
      key_(std::move(key)),
      line_(line) {}

}  // namespace gaitopt
