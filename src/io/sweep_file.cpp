#include "gaitopt/io/sweep_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "gaitopt/gait/cost_of_transport.hpp"
#include "gaitopt/gait/constraint_summary.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/csv_table.hpp"

namespace gaitopt {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxCsvLineBytes = 4096;

double parseNumber(const std::string& field, const std::string& what, const std::string& text) {
  const std::optional<double> v = parseDecimal(field);
  if (!v)
    throw std::invalid_argument("speed range '" + printable(text) + "': " + what + " '" +
                                printable(field) + "' is not a finite number");
  return *v;
}

// Three significant digits, for the progress line.
std::string threeDigits(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// An empty field for a value not computed.
std::optional<double> field(bool available, double v) {
  return available ? finiteOrAbsent(v) : std::nullopt;
}

// One row of a sweep.csv, every column typed and range-checked (docs/commands/sweep.md);
// throws std::invalid_argument naming `where` (file:line) and the column. Returns the speed.
double checkSweepRow(const std::vector<std::string>& f, const std::string& where) {
  const std::vector<std::string> names = splitFields(kSweepCsvHeader);
  const auto bad = [&](std::size_t c, const std::string& problem) {
    return std::invalid_argument(where + ": column " + names[c] + ": '" + printable(f[c]) +
                                 "' " + problem);
  };
  const std::optional<double> speed = parseDecimal(f[0]);
  if (!speed || !(*speed > 0.0) || *speed > kMaxWalkingSpeed)
    throw bad(0, "is not a speed in (0, " + speedText(kMaxWalkingSpeed) + "] m/s");
  if (!parseOptimizationStatus(f[1]))
    throw bad(1, "is not a status (optimal, infeasible, max_iter, failed)");
  for (std::size_t c = 2; c <= 9; ++c) {  // criteria, cost of transport, step, durations
    const std::optional<double> v = parseDecimal(f[c]);
    if (!f[c].empty() && (!v || (c >= 8 && *v < 0.0)))
      throw bad(c, c >= 8 ? "is not a duration >= 0 s (or empty)" : "is not a number (or empty)");
  }
  if (f[10].empty() || f[10].size() > 9 ||
      f[10].find_first_not_of("0123456789") != std::string::npos)
    throw bad(10, "is not a non-negative integer");
  const std::optional<double> wall = parseDecimal(f[11]);
  if (!wall || *wall < 0.0) throw bad(11, "is not a duration >= 0 s");
  for (std::size_t c : {12, 14, 16}) {  // min_violation, blocking_value, blocking_multiplier
    const std::optional<double> v = parseDecimal(f[c]);
    if (!f[c].empty() && (!v || (c == 16 && *v < 0.0)))
      throw bad(c, c == 16 ? "is not a multiplier >= 0 (or empty)" : "is not a number (or empty)");
  }
  for (std::size_t c : {13, 15})  // blocking_constraint, blocking_unit: names, no quoting
    if (f[c].find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                               "_ +-^/()") != std::string::npos)
      throw bad(c, "is not a constraint name or unit (letters, digits, _ +-^/() and spaces)");
  return *speed;
}

}  // namespace

std::vector<double> parseSpeedRange(const std::string& text) {
  const std::vector<std::string> f = splitFields(text, ':');
  if (f.size() != 3)
    throw std::invalid_argument("speed range '" + text +
                                "': expected start:stop:step in m/s, e.g. 0.2:1.0:0.05");
  const double start = parseNumber(f[0], "start", text);
  const double stop = parseNumber(f[1], "stop", text);
  const double step = parseNumber(f[2], "step", text);
  if (start <= 0.0)
    throw std::invalid_argument("speed range '" + text + "': start must be > 0 m/s");
  if (stop < start)
    throw std::invalid_argument("speed range '" + text + "': stop must be >= start");
  if (stop > kMaxWalkingSpeed)
    throw std::invalid_argument("speed range '" + text + "': stop must be <= " +
                                speedText(kMaxWalkingSpeed) + " m/s");
  if (step <= 0.0) throw std::invalid_argument("speed range '" + text + "': step must be > 0 m/s");
  const double intervals = std::floor((stop - start) / step + 1e-9);
  if (intervals + 1.0 > kMaxSweepSpeeds)
    throw std::invalid_argument("speed range '" + text + "': more than " +
                                std::to_string(kMaxSweepSpeeds) + " speeds");
  std::vector<double> out;
  for (int k = 0; k <= static_cast<int>(intervals); ++k)
    out.push_back(std::round((start + k * step) * 1e12) / 1e12);
  return out;
}

Shard parseShard(const std::string& text) {
  const std::vector<std::string> f = splitFields(text, '/');
  auto integer = [&](const std::string& s, const char* what) {
    if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
      throw std::invalid_argument("shard '" + printable(text) + "': " + what + " '" +
                                  printable(s) +
                                  "' is not a non-negative integer (expected i/n, i = 0 … n-1)");
    if (s.size() > 5 || std::stoi(s) > kMaxSweepSpeeds)
      throw std::invalid_argument("shard '" + text + "': " + what + " " + s + " exceeds " +
                                  std::to_string(kMaxSweepSpeeds) + ", the largest number of speeds");
    return std::stoi(s);
  };
  if (f.size() != 2)
    throw std::invalid_argument("shard '" + printable(text) +
                                "': expected i/n with 0 <= i < n, e.g. 0/4");
  Shard shard{integer(f[0], "index"), integer(f[1], "count")};
  if (shard.count < 1) throw std::invalid_argument("shard '" + text + "': n must be >= 1");
  if (shard.index >= shard.count)
    throw std::invalid_argument("shard '" + text + "': index must be < n (0-based: 0 … " +
                                std::to_string(shard.count - 1) + ")");
  return shard;
}

const char* const kSweepCsvHeader =
    "speed,status,C_Gamma,C_E,W,C_frott,CoT,step_length,T_SS,T_DS,iterations,wall_time_s,"
    "min_violation,blocking_constraint,blocking_value,blocking_unit,blocking_multiplier";

std::string sweepCsvRow(const GaitEvaluator& ev, const SweepPoint& p) {
  const GaitEvaluation<double>& e = p.result.evaluation;
  const bool criteria = e.defined() && e.motion_computed;
  const bool timing = zeroDynamicsComputed(ev, e);
  CsvRow row;
  row.number(p.speed).text(optimizationStatusName(p.result.status));
  row.number(field(criteria, e.C_Gamma)).number(field(criteria, e.C_E));
  row.number(field(criteria, e.W)).number(field(criteria, e.C_frott));
  row.number(field(criteria, costOfTransport(ev.model(), e.C_E)));
  row.number(field(true, p.result.parameters[kStepLength])).number(field(timing, e.T_SS));
  row.number(field(true, p.result.parameters[kTDS])).integer(p.total_iterations);
  row.number(p.total_wall_time_s);
  // The elastic problem's evidence: s* whenever it ran, the blocking row of a certificate.
  const InfeasibilityCertificate* c = p.certificate ? &*p.certificate : nullptr;
  row.number(field(c != nullptr, c ? c->min_violation : 0.0));
  if (!c || !c->infeasible()) return row.empty().empty().empty().empty().str();
  const BlockingConstraint& b = c->blocking.front();
  return row.text(b.name).number(b.value).text(b.unit).number(b.multiplier).str();
}

std::string sweepCsv(const GaitEvaluator& ev, const std::vector<SweepPoint>& points) {
  std::string out = std::string(kSweepCsvHeader) + "\n";
  for (const SweepPoint& p : points) out += sweepCsvRow(ev, p) + "\n";
  return out;
}

std::string sweepEvidenceText(const SweepPoint& p) {
  if (!p.certificate || isOptimal(p.result)) return "";
  const InfeasibilityCertificate& c = *p.certificate;
  if (!c.infeasible())
    return c.min_violation <= kFeasibilityTolerance
               ? "rows can be met: not shown infeasible  "
               : "no certificate (elastic problem not first-order)  ";
  const BlockingConstraint& b = c.blocking.front();
  return "blocked by " + b.name + " (+" + threeDigits(b.value) + " " + b.unit +
         ", multiplier " + threeDigits(b.multiplier) + ")  ";
}

std::string mergeSweepCsvs(const std::vector<std::string>& texts,
                           const std::vector<std::string>& names) {
  const std::size_t columns = splitFields(kSweepCsvHeader).size();
  std::vector<std::pair<double, std::string>> rows;
  std::vector<std::string> origin;
  for (std::size_t t = 0; t < texts.size(); ++t) {
    const std::string name =
        printable(t < names.size() ? names[t] : "input " + std::to_string(t + 1));
    if (texts[t].size() > kMaxSweepCsvBytes)
      throw std::invalid_argument(name + ": larger than " + std::to_string(kMaxSweepCsvBytes) +
                                  " bytes (limit)");
    std::istringstream in(texts[t]);
    std::string line;
    if (!std::getline(in, line)) throw std::invalid_argument(name + ": empty file, no header");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line != kSweepCsvHeader)
      throw std::invalid_argument(name + ": header '" + printable(line) + "' differs from '" +
                                  kSweepCsvHeader + "'");
    int line_no = 1;
    while (std::getline(in, line)) {
      ++line_no;
      const std::string where = name + ":" + std::to_string(line_no);
      if (line.size() > kMaxCsvLineBytes)
        throw std::invalid_argument(where + ": line longer than " +
                                    std::to_string(kMaxCsvLineBytes) + " bytes (limit)");
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.empty()) continue;
      const std::vector<std::string> f = splitFields(line);
      if (f.size() != columns)
        throw std::invalid_argument(where + ": expected " + std::to_string(columns) +
                                    " fields, got " + std::to_string(f.size()));
      if (static_cast<int>(rows.size()) >= kMaxSweepSpeeds)
        throw std::invalid_argument(where + ": more than " + std::to_string(kMaxSweepSpeeds) +
                                    " rows (limit)");
      rows.emplace_back(checkSweepRow(f, where), line);
      origin.push_back(where);
    }
  }
  std::vector<std::size_t> idx(rows.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::stable_sort(idx.begin(), idx.end(),
                   [&](std::size_t a, std::size_t b) { return rows[a].first < rows[b].first; });
  std::string out = std::string(kSweepCsvHeader) + "\n";
  for (std::size_t k = 0; k < idx.size(); ++k) {
    if (k > 0 && rows[idx[k]].first - rows[idx[k - 1]].first <= kSweepSpeedTolerance)
      throw std::invalid_argument("speed " + speedText(rows[idx[k]].first) + " appears twice: " +
                                  origin[idx[k - 1]] + " and " + origin[idx[k]]);
    out += rows[idx[k]].second + "\n";
  }
  return out;
}

namespace {

// A shard's sweep.csv: a regular file within the size limit (a directory would read as empty).
std::string readShardSweepCsv(const fs::path& path) {
  const std::string name = printable(path.string());
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw std::invalid_argument("'" + name + "' is missing or not a regular file");
  if (fs::file_size(path, ec) > kMaxSweepCsvBytes)
    throw std::invalid_argument("'" + name + "' is larger than " +
                                std::to_string(kMaxSweepCsvBytes) + " bytes (limit)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument("cannot read '" + name + "'");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

std::string mergeShardSweepCsvs(const std::vector<std::string>& shard_dirs) {
  std::vector<std::string> texts, names;
  for (const std::string& dir : shard_dirs) {
    const fs::path csv = fs::path(dir) / "sweep.csv";
    names.push_back(csv.string());
    texts.push_back(readShardSweepCsv(csv));
  }
  return mergeSweepCsvs(texts, names);
}

SweepCsvCount countSweepCsvRows(const std::string& csv) {
  SweepCsvCount n;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    ++n.rows;
    const std::vector<std::string> f = splitFields(line);
    if (f.size() > 1 && parseOptimizationStatus(f[1]) == OptimizationStatus::Optimal) ++n.optimal;
  }
  return n;
}

std::string sweepFolderName(double speed, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "v%.*f", decimals, speed);
  return buf;
}

int sweepFolderDecimals(const std::vector<double>& speeds) {
  for (int d = 3; d < 12; ++d) {
    std::vector<std::string> names;
    for (double v : speeds) names.push_back(sweepFolderName(v, d));
    std::sort(names.begin(), names.end());
    if (std::adjacent_find(names.begin(), names.end()) == names.end()) return d;
  }
  return 12;
}

void writeSweepMembers(JsonWriter& w, const SweepPoint& p) {
  w.key("sweep").beginObject();
  w.key("speed").value(p.speed);
  w.key("warm_started").value(p.warm_started);
  w.key("from_speed").value(p.from_speed);  // null (NaN) when started from the default guess
  w.key("attempts").value(p.attempts);
  w.key("total_iterations").value(p.total_iterations);
  w.key("total_wall_time_s").value(p.total_wall_time_s);
  w.endObject();
}

OptimizeConfig freeSpeedConfig(const OptimizeConfig& config) {
  OptimizeConfig free = config;
  free.speed.reset();
  free.options.target_speed = 0.0;
  return free;
}

OptimizationOutputs sweepPointOutputs(const OptimizeConfig& config, const SweepPoint& p,
                                      const std::string& dir) {
  OptimizeConfig speed_config = config;
  speed_config.speed = p.speed;
  speed_config.options.target_speed = p.speed;
  const GaitEvaluator evaluator(speed_config.robot, speed_config.options,
                                speed_config.model_options);
  return optimizationOutputs(evaluator, speed_config, p.result, dir,
                             [&](JsonWriter& w) { writeSweepMembers(w, p); });
}

}  // namespace gaitopt
