#include "cli_common.hpp"

#include "gaitopt/io/config_error.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace gaitopt::cli {

std::string shortNumber(double v, const char* format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

CLI::Validator numberWithin(double lo, double hi, bool lo_open, const std::string& unit) {
  const std::string range = std::string(lo_open ? "(" : "[") + shortNumber(lo, "%g") + ", " +
                            shortNumber(hi, "%g") + "]" + (unit.empty() ? "" : " " + unit);
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(s.c_str(), &end);
        const bool plain =
            !s.empty() && s.find_first_not_of("0123456789+-.eE") == std::string::npos;
        if (!plain || end != s.c_str() + s.size() || !std::isfinite(v))
          return "'" + printable(s) + "' is not a finite number";
        if ((lo_open ? v <= lo : v < lo) || v > hi)
          return "must be in " + range + ", got " + printable(s);
        return "";
      },
      "NUMBER in " + range);
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

std::function<bool(const std::string&)> ourOutputs(const SolverSettings* solver) {
  std::string ipopt_output;
  if (solver) {
    for (const auto& [key, value] : solver->ipopt_options)
      if (key == "output_file") ipopt_output = value;
  }
  return [ipopt_output](const std::string& name) {
    const bool speed_folder = name.size() > 1 && name[0] == 'v' &&
                              name.find_first_not_of("0123456789.", 1) == std::string::npos;
    return name == "summary.json" || name == "gait.yaml" || name == "trajectory.csv" ||
           name == "sweep.csv" || speed_folder || (!ipopt_output.empty() && name == ipopt_output);
  };
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
