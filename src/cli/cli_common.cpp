#include "cli_common.hpp"

#include "data_files.hpp"

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/csv_table.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "gaitopt/io/summary_file.hpp"
#include "gaitopt/opt/gait_problem.hpp"
#include "gaitopt/opt/result_order.hpp"

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
        const std::optional<double> v = parseDecimal(s);
        if (!v) return decimalProblem(s);
        if ((lo_open ? *v <= lo : *v < lo) || *v > hi)
          return "must be in " + range + ", got " + printable(s);
        return "";
      },
      "NUMBER in " + range);
}

CLI::Validator integerWithin(long long lo, long long hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        const std::size_t digits = s.find_first_not_of('-') == 1 ? 1 : 0;  // one leading '-'
        const bool whole = s.size() > digits && s.size() - digits <= 18 &&
                           s.find_first_not_of("0123456789", digits) == std::string::npos;
        if (!whole) return "'" + printable(s) + "' is not a whole decimal number";
        const long long v = std::stoll(s);
        if (v < lo || v > hi) return "must be in " + range + ", got " + printable(s);
        return "";
      },
      "INTEGER in " + range);
}

void requireSampleRows(const std::string& options, double steps, double step_duration,
                       double rate) {
  const double rows = steps * step_duration * rate;
  if (rows > kMaxSampleRows)
    throw CLI::ValidationError(
        options, shortNumber(steps, "%g") + " steps of " + shortNumber(step_duration, "%.3g") +
                     " s at " + shortNumber(rate, "%g") + " Hz make " + shortNumber(rows, "%.3g") +
                     " rows, more than the limit of " + shortNumber(kMaxSampleRows, "%g") +
                     "; give fewer steps or a lower rate");
}

std::function<bool(const std::string&)> ourOutputs(const SolverSettings* solver) {
  std::vector<std::string> names = {"summary.json", "gait.yaml", "trajectory.csv", "sweep.csv"};
  if (solver) {
    for (const auto& [key, value] : solver->ipopt_options)
      if (key == "output_file") names.push_back(value);
  }
  const std::function<bool(const std::string&)> files = ourFiles(std::move(names));
  return [files](const std::string& name) {
    const bool speed_folder = name.size() > 1 && name[0] == 'v' &&
                              name.find_first_not_of("0123456789.", 1) == std::string::npos;
    return speed_folder || files(name);
  };
}

std::function<bool(const std::string&)> ourFiles(std::vector<std::string> names) {
  // A figure `gaitopt plot` made of the old result goes with it (docs/commands/plot.md).
  for (std::string& figure : plotFigureNames()) names.push_back(std::move(figure));
  return [names = std::move(names)](const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
}

std::optional<double> criterionOf(const OptimizationResult& r, Criterion c) {
  return resultCriterion(r, c);
}

std::string criterionText(const OptimizationResult& r, Criterion c, const char* format) {
  const std::optional<double> v = criterionOf(r, c);
  return v ? shortNumber(*v, format) : std::string("n/a");
}

const char* criterionUnit(Criterion c) { return c == Criterion::Torque ? "N^2*m*s" : "J/m"; }

std::string progressText(const GaitEvaluator& ev, const GaitEvaluation<double>& e, Criterion c) {
  std::string text;
  if (e.motion_computed)
    text = std::string(criterionName(c)) + " " + shortNumber(criterionValue(e, c), "%.1f") + " " +
           criterionUnit(c);
  else
    text = std::string(criterionName(c)) + " n/a (step undefined at level " +
           std::to_string(e.failed_level) + ")";
  // The worst entry relative to its group's typical magnitude, as the optimiser weighs them.
  int worst_group = -1;
  double worst_scaled = -1.0, worst_value = 0.0;
  const bool evaluated = static_cast<int>(e.g.size()) == ev.layout().size();
  for (int id = 0; evaluated && id < kNumConstraintGroups; ++id) {
    const ConstraintGroup& g = ev.layout()[id];
    for (int k = g.offset; k < g.offset + g.count; ++k) {
      if (e.state[k] == ConstraintState::NotComputed) continue;
      const double scaled = e.g[k] / constraintScale(ev.layout(), ev.model(), k);
      // The shared tolerance (gait/feasibility.hpp): what is within it holds.
      if (!(scaled > kFeasibilityTolerance)) continue;
      if (scaled > worst_scaled) {
        worst_scaled = scaled;
        worst_value = e.g[k];
        worst_group = id;
      }
    }
  }
  if (worst_group < 0) return text + "  constraints hold at the nodes";
  return text + "  worst " + ev.layout()[worst_group].name + " +" +
         shortNumber(worst_value, "%.3g") + " " + ev.layout()[worst_group].unit;
}

std::string elapsedAndRemaining(double elapsed_s, int done, int total) {
  std::string s = "elapsed " + shortNumber(elapsed_s, "%.1f") + " s";
  if (done > 0 && done < total)
    s += ", remaining ~" + shortNumber(elapsed_s / done * (total - done), "%.1f") + " s";
  return s;
}

void addDsControlOption(CLI::App* cmd, std::string& target) {
  cmd->add_option("--ds-control", target,
                  "DS control of alpha: cubic, time_optimal (the bang-bang law (4.1) on the "
                  "exact bounds of the LPs (4.14))")
      ->capture_default_str()
      ->check(CLI::IsMember({"cubic", "time_optimal"}));
}

DsAlphaControl dsAlphaControlOf(const std::string& name) {
  return name == "cubic" ? DsAlphaControl::Cubic : DsAlphaControl::TimeOptimal;
}

}  // namespace gaitopt::cli
