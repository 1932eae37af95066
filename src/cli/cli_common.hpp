#pragma once
// Helpers shared by the `gaitopt` subcommands: number formatting, the --out check and the
// criterion of an optimisation result.
#include <CLI/CLI.hpp>
#include <chrono>
#include <functional>
#include <ostream>
#include <optional>
#include <string>
#include <vector>

#include "gaitopt/opt/optimizer.hpp"
#include "gaitopt/sim/closed_loop.hpp"
#include "gaitopt/opt/gait_problem.hpp"
#include "optimize_progress.hpp"  // OptimizeProgress, for the optimising commands

namespace gaitopt::cli {

// `v` formatted with the printf `format` (one floating-point conversion).
std::string shortNumber(double v, const char* format = "%.6g");

// Every numeric option: a decimal number in io's one syntax (parseDecimal: no inf, nan, hex,
// blanks or trailing text) in [lo, hi] ((lo, hi] when lo_open); messages quote the value
// printable, cut at 200 bytes.
CLI::Validator numberWithin(double lo, double hi, bool lo_open = false,
                            const std::string& unit = "");
// Rows of a sampled walk (export, simulate) beyond which a run is refused: 2e5 rows keep it
// within about 1 GB and a minute (docs/reliability.md; scripts/measure_input_limits.sh).
constexpr double kMaxSampleRows = 2e5;

// Bad input (CLI::ValidationError at `options`) when `steps` steps of `step_duration` s sampled
// at `rate` Hz make more than kMaxSampleRows rows; checked before any sampling.
void requireSampleRows(const std::string& options, double steps, double step_duration,
                       double rate);

// Whole-number options: digits with at most one leading '-' (no '+', point, exponent, hex), in
// [lo, hi]: `--seed -1` is refused, not wrapped.
CLI::Validator integerWithin(long long lo, long long hi);

// Whether `name` is an entry gaitopt writes into an output directory (summary.json,
// gait.yaml, trajectory.csv, sweep.csv, v<speed> folders, the Ipopt output_file of `solver`, or
// a figure `gaitopt plot` drew of the result); OutputTransaction::directory refuses an existing
// --out holding anything else, and replaces the rest with the new result.
std::function<bool(const std::string&)> ourOutputs(const SolverSettings* solver = nullptr);
// The same for a command that writes `names`.
std::function<bool(const std::string&)> ourFiles(std::vector<std::string> names);

// The criterion of a result; it exists only for a defined step whose motion was computed.
std::optional<double> criterionOf(const OptimizationResult& r, Criterion c);

// criterionOf formatted with `format`, or "n/a".
std::string criterionText(const OptimizationResult& r, Criterion c, const char* format = "%.6g");

// Unit of a criterion's value: "N^2*m*s" for C_Gamma (3.28), "J/m" for C_E and W.
const char* criterionUnit(Criterion c);

// One progress text in the user's units: the criterion with its unit and the worst violated
// constraint (largest value relative to its group's scale) with its name, value and unit, e.g.
// "C_Gamma 9122.8 N^2*m*s  worst torque_envelope_ss +3.2 N m". "constraints hold" when none is
// violated; for a step without motion, the failed level.
std::string progressText(const GaitEvaluator& evaluator, const GaitEvaluation<double>& e,
                         Criterion c);

// "elapsed 12.3 s, remaining ~45.6 s" after `done` of `total` items in `elapsed_s` seconds.
// `--ds-control cubic|time_optimal` (simulate, stability) into `target`.
void addDsControlOption(CLI::App* cmd, std::string& target);
DsAlphaControl dsAlphaControlOf(const std::string& name);

std::string elapsedAndRemaining(double elapsed_s, int done, int total);

}  // namespace gaitopt::cli
