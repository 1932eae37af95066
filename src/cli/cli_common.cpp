#include "cli_common.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <system_error>

namespace gaitopt::cli {

std::string shortNumber(double v, const char* format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

void requireDirectoryOrAbsent(const std::string& out) {
  std::error_code ec;
  if (std::filesystem::exists(out, ec) && !std::filesystem::is_directory(out, ec))
    throw CLI::ValidationError("--out", "'" + out + "' exists and is not a directory");
}

void requireFileOutput(const std::string& out) {
  std::error_code ec;
  if (std::filesystem::is_directory(out, ec))
    throw CLI::ValidationError("--out", "'" + out + "' is a directory, a file is expected");
}

std::optional<double> criterionOf(const OptimizationResult& r, Criterion c) {
  if (!r.evaluation.motion_computed || !r.evaluation.defined()) return std::nullopt;
  return criterionValue(r.evaluation, c);
}

std::string criterionText(const OptimizationResult& r, Criterion c, const char* format) {
  const std::optional<double> v = criterionOf(r, c);
  return v ? shortNumber(*v, format) : std::string("n/a");
}

}  // namespace gaitopt::cli
