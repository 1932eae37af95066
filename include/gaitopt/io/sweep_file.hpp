#pragma once
// The files of a speed sweep (opt/continuation.hpp): sweep.csv (writing, and merging the
// sweep.csv of several shards), the per-speed folders with their summary.json members, and the
// command-line syntax of the speed range and of a shard.
#include <cstddef>
#include <string>
#include <vector>

#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/io/optimize_output.hpp"
#include "gaitopt/opt/continuation.hpp"

namespace gaitopt {

// "start:stop:step" [m/s], stop included when reached within a rounding tolerance (1e-9 step);
// values are rounded to 1e-12 m/s so 0.2 + 0.1 gives 0.3. Throws std::invalid_argument when the
// text is not three finite numbers, start ≤ 0, stop < start, step ≤ 0 or more than 10000 speeds.
std::vector<double> parseSpeedRange(const std::string& text);

// Shard "i/n", i 0-based (0 ≤ i < n); throws std::invalid_argument otherwise.
Shard parseShard(const std::string& text);

// sweep.csv
constexpr std::size_t kMaxSweepCsvBytes = std::size_t{4} << 20;  // read limit per file (4 MiB)
extern const char* const kSweepCsvHeader;  // speed,status,C_Gamma,...,wall_time_s (no newline)
// One row (no newline): full precision, empty fields where undefined; iterations and wall time
// are totals over the speed's attempts.
std::string sweepCsvRow(const GaitEvaluator& evaluator, const SweepPoint& point);
std::string sweepCsv(const GaitEvaluator& evaluator, const std::vector<SweepPoint>& points);

// What the elastic problem (opt/infeasibility_certificate.hpp) showed for a speed without an
// optimum, for the progress line: "blocked by joint_limits_ss knee 2 upper at SS node 16
// (+0.0249 rad, multiplier 0.353)  ", "rows can be met: not shown infeasible  ", "no
// certificate (elastic problem not first-order)  "; empty for an optimal speed or one
// without the elastic problem.
std::string sweepEvidenceText(const SweepPoint& point);

// Concatenation of several sweep.csv texts (`names` label them in messages), rows sorted by
// speed. Strict: every column typed and range-checked (speed in (0, 10] m/s, a known status,
// numbers or empty fields, durations >= 0, an integer iteration count); CRLF line ends, blank
// lines and a missing final newline are accepted. Throws std::invalid_argument naming
// file:line and the column if a header differs from kSweepCsvHeader, a row is malformed, a
// speed appears twice (within 1e-9 m/s), or a limit is exceeded (kMaxSweepCsvBytes per text,
// 4096 bytes per line, 10000 rows in all).
std::string mergeSweepCsvs(const std::vector<std::string>& texts,
                           const std::vector<std::string>& names);

// mergeSweepCsvs of DIR/sweep.csv for each shard directory; std::invalid_argument also when a
// file is missing, not a regular file, unreadable or larger than kMaxSweepCsvBytes.
std::string mergeShardSweepCsvs(const std::vector<std::string>& shard_dirs);

// Rows of a merged sweep.csv, and how many of them are optimal.
struct SweepCsvCount {
  std::size_t rows = 0, optimal = 0;
};
SweepCsvCount countSweepCsvRows(const std::string& csv);

// Sub-folder of one speed: "v" + fixed-point speed with `decimals` digits ("v0.500");
// sweepFolderDecimals gives the fewest decimals ≥ 3 (at most 12) that keep the list's names
// distinct.
std::string sweepFolderName(double speed, int decimals);
int sweepFolderDecimals(const std::vector<double>& speeds);

// The sweep's own members of a speed's summary.json (`sweep`: speed, warm start, attempts).
void writeSweepMembers(JsonWriter& w, const SweepPoint& point);

// The free-speed problem of a configuration: no target speed (the sweep sets each speed).
OptimizeConfig freeSpeedConfig(const OptimizeConfig& config);

// A speed's outputs, as `gaitopt optimize` with `speed` set to it would write them into `dir`,
// plus the sweep's members.
OptimizationOutputs sweepPointOutputs(const OptimizeConfig& config, const SweepPoint& point,
                                      const std::string& dir);

}  // namespace gaitopt
