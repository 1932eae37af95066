#pragma once
// Helpers shared by the `gaitopt` subcommands: number formatting, the --out check and the
// criterion of an optimisation result.
#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>

#include "gaitopt/opt/optimizer.hpp"
#include "gaitopt/opt/gait_problem.hpp"

namespace gaitopt::cli {

// `v` formatted with the printf `format` (one floating-point conversion).
std::string shortNumber(double v, const char* format = "%.6g");

// Command-line numbers: a plain decimal number (no inf, nan, hex or trailing text) in
// [lo, hi] ((lo, hi] when lo_open), echoed as written in the message.
CLI::Validator numberWithin(double lo, double hi, bool lo_open, const std::string& unit);

// Bad input (CLI::ValidationError at --out) when `out` exists and is not a directory; called
// before anything is written.
void requireDirectoryOrAbsent(const std::string& out);

// Bad input (CLI::ValidationError at --out) when the output file `out` is a directory.
void requireFileOutput(const std::string& out);

// Whether `name` is an entry gaitopt writes into an output directory (summary.json,
// gait.yaml, trajectory.csv, sweep.csv, v<speed> folders, or the Ipopt output_file of
// `solver`); StagedDirectory refuses an existing --out holding anything else.
std::function<bool(const std::string&)> ourOutputs(const SolverSettings* solver = nullptr);

// The criterion of a result; it exists only for a defined step whose motion was computed.
std::optional<double> criterionOf(const OptimizationResult& r, Criterion c);

// criterionOf formatted with `format`, or "n/a".
std::string criterionText(const OptimizationResult& r, Criterion c, const char* format = "%.6g");

}  // namespace gaitopt::cli
