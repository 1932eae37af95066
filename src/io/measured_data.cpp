#include "gaitopt/io/measured_data.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/io/tab_text.hpp"

namespace gaitopt {

namespace {

const std::array<const char*, 9> kRequired = {"t",      "alpha",  "delta1", "delta2", "delta3",
                                              "delta4", "phase",  "stance", "step"};
const std::array<const char*, 4> kTorque = {"gamma1", "gamma2", "gamma3", "gamma4"};
const std::array<const char*, 4> kReactions = {"R1x", "R1z", "R2x", "R2z"};
const std::array<const char*, 2> kCop = {"cop1x", "cop2x"};

std::vector<std::string> splitCsvLine(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  std::vector<std::string> cells = splitFields(line);
  for (std::string& cell : cells) cell = trimBlanks(cell);
  return cells;
}

// Locates errors: "<file>:<line>: row <r>, column '<c>': <problem>" (row 1 = first data row).
class CsvContext {
 public:
  explicit CsvContext(std::string file) : file_(std::move(file)) {}
  ConfigError error(int line, const std::string& column, const std::string& problem) const {
    const std::string where =
        line > 1 ? "row " + std::to_string(line - 1) + ", column '" + column + "': "
                 : "column '" + column + "': ";
    return ConfigError(file_, "", line, where + problem);
  }
  ConfigError fileError(const std::string& problem) const {
    return ConfigError(file_, "", 0, problem);
  }

 private:
  std::string file_;
};

class RowReader {
 public:
  RowReader(const CsvContext& ctx, const std::map<std::string, int>& columns,
            const std::vector<std::string>& cells, int line)
      : ctx_(ctx), columns_(columns), cells_(cells), line_(line) {}
  const std::string& text(const std::string& c) const { return cells_[columns_.at(c)]; }
  double number(const std::string& c) const {
    if (const std::optional<double> v = parseDecimal(text(c))) return *v;
    throw ctx_.error(line_, c, decimalProblem(text(c)));
  }
  template <std::size_t N> Vec4 four(const std::array<const char*, N>& names) const {
    return Vec4(number(names[0]), number(names[1]), number(names[2]), number(names[3]));
  }
  ConfigError error(const std::string& c, const std::string& problem) const {
    return ctx_.error(line_, c, problem);
  }

 private:
  const CsvContext& ctx_;
  const std::map<std::string, int>& columns_;
  const std::vector<std::string>& cells_;
  int line_;
};

template <std::size_t N>
bool optionalGroup(const CsvContext& ctx, const std::map<std::string, int>& columns,
                   const std::array<const char*, N>& names) {
  std::size_t present = 0;
  for (const char* n : names) present += columns.count(n);
  if (present != 0 && present != N)
    for (const char* n : names)
      if (!columns.count(n)) throw ctx.error(1, n, "missing: give all of its group or none");
  return present == N;
}

std::map<std::string, int> readHeader(const CsvContext& ctx, const std::string& header) {
  std::map<std::string, int> columns;
  const std::vector<std::string> names = splitCsvLine(header);
  for (std::size_t i = 0; i < names.size(); ++i) {
    bool known = false;
    for (const auto& [group, n] : {std::pair{kRequired.data(), kRequired.size()},
                                   {kTorque.data(), kTorque.size()},
                                   {kReactions.data(), kReactions.size()},
                                   {kCop.data(), kCop.size()}})
      for (std::size_t k = 0; k < n; ++k) known = known || names[i] == group[k];
    if (!known) throw ctx.error(1, printable(names[i]), "unknown column");
    if (!columns.emplace(names[i], static_cast<int>(i)).second)
      throw ctx.error(1, names[i], "duplicate column");
  }
  for (const char* n : kRequired)
    if (!columns.count(n)) throw ctx.error(1, n, "missing required column");
  return columns;
}

void appendRow(const RowReader& row, MeasuredData& d) {
  const double t = row.number("t");
  if (!d.t.empty() && !(t > d.t.back()))
    throw row.error("t", "time must increase, got " + formatDouble(t) + " after " +
                             formatDouble(d.t.back()));
  d.t.push_back(t);
  const std::array<const char*, 5> angles = {"alpha", "delta1", "delta2", "delta3", "delta4"};
  for (const char* c : angles)
    if (std::abs(row.number(c)) > kMaxMeasuredAngle)
      throw row.error(c, "angle " + printable(row.text(c)) + " rad is beyond two turns (" +
                             formatDouble(kMaxMeasuredAngle) + " rad): not radians of a joint");
  d.q.emplace_back(row.number("alpha"), row.number("delta1"), row.number("delta2"),
                   row.number("delta3"), row.number("delta4"));
  const std::string& ph = row.text("phase");
  if (ph != "SS" && ph != "DS") throw row.error("phase", "must be SS or DS, got '" + printable(ph) + "'");
  d.phase.push_back(ph == "SS" ? Phase::SingleSupport : Phase::DoubleSupport);
  const std::string& st = row.text("stance");
  if (st != "left" && st != "right")
    throw row.error("stance", "must be left or right, got '" + printable(st) + "'");
  d.stance.push_back(st == "left" ? Stance::Left : Stance::Right);
  const double step = row.number("step");
  if (step != std::floor(step) || std::abs(step) > 1e15)
    throw row.error("step", "must be an integer, got '" + printable(row.text("step")) + "'");
  if (!d.step.empty() && step < d.step.back())
    throw row.error("step", "must not decrease, got " + row.text("step") + " after " +
                                std::to_string(d.step.back()));
  d.step.push_back(static_cast<long>(step));
  if (d.has_torque) d.gamma.push_back(row.four(kTorque));
  if (d.has_reactions) d.reactions.push_back(row.four(kReactions));
  if (d.has_cop) d.cop.push_back({row.number(kCop[0]), row.number(kCop[1])});
}

void checkSteps(const CsvContext& ctx, const MeasuredData& d, const std::vector<int>& lines) {
  int steps = 0;
  for (std::size_t i = 0; i < d.size();) {
    std::size_t k = i;
    while (k < d.size() && d.step[k] == d.step[i]) ++k;
    if (k - i < static_cast<std::size_t>(kMinSamplesPerStep))
      throw ctx.error(lines[i], "step",
                      "step " + std::to_string(d.step[i]) + " has " + std::to_string(k - i) +
                          " samples, fewer than " + std::to_string(kMinSamplesPerStep));
    ++steps;
    i = k;
  }
  if (steps < kMinSteps)
    throw ctx.fileError("column 'step': " + std::to_string(steps) + " steps, fewer than " +
                        std::to_string(kMinSteps));
}

// Time may jump only between steps: inside one, no gap over kMaxGapInSamples times the median
// sample interval.
void checkTimeGaps(const CsvContext& ctx, const MeasuredData& d, const std::vector<int>& lines) {
  std::vector<double> gaps;
  for (std::size_t i = 1; i < d.size(); ++i)
    if (d.step[i] == d.step[i - 1]) gaps.push_back(d.t[i] - d.t[i - 1]);
  if (gaps.empty()) return;
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  const double median = gaps[gaps.size() / 2];
  for (std::size_t i = 1; i < d.size(); ++i) {
    const double gap = d.t[i] - d.t[i - 1];
    if (d.step[i] == d.step[i - 1] && gap > kMaxGapInSamples * median)
      throw ctx.error(lines[i], "t",
                      "gap of " + formatDouble(gap) + " s inside step " +
                          std::to_string(d.step[i]) + ", over " + formatDouble(kMaxGapInSamples) +
                          " times the median sample interval (" + formatDouble(median) +
                          " s): time may jump only between steps");
  }
}

}  // namespace

MeasuredData readMeasuredCsv(const std::string& path) {
  const CsvContext ctx(path);
  // Size limit, NUL bytes refused and CR dropped as for the other tables (tab_text.hpp).
  const std::vector<std::string> text = readTableLines(path);
  if (text.empty()) throw ctx.fileError("empty file: expected a header row");
  const std::map<std::string, int> columns = readHeader(ctx, text[0]);
  MeasuredData d;
  d.has_torque = optionalGroup(ctx, columns, kTorque);
  d.has_reactions = optionalGroup(ctx, columns, kReactions);
  if (!d.has_torque && !d.has_reactions)
    throw ctx.error(1, "gamma1", "no torque (gamma1..gamma4) and no reaction (R1x..R2z) columns");
  d.has_cop = optionalGroup(ctx, columns, kCop);
  if (d.has_cop && !d.has_reactions)
    throw ctx.error(1, "cop1x", "centres of pressure need the reaction columns R1x..R2z");
  std::vector<int> lines;
  for (std::size_t i = 1; i < text.size(); ++i) {
    const std::string& line = text[i];
    const int number = static_cast<int>(i) + 1;
    if (line.empty()) continue;
    if (lines.size() == kMaxMeasuredRows)
      throw ctx.error(number, "", "more than " + std::to_string(kMaxMeasuredRows) +
                                      " samples (limit)");
    const std::vector<std::string> cells = splitCsvLine(line);
    if (cells.size() != columns.size())
      throw ctx.error(number, "", "has " + std::to_string(cells.size()) + " cells, header has " +
                                      std::to_string(columns.size()));
    appendRow(RowReader(ctx, columns, cells, number), d);
    lines.push_back(number);
  }
  checkSteps(ctx, d, lines);
  checkTimeGaps(ctx, d, lines);
  return d;
}

void requirePlausibleTorques(const MeasuredData& data, const RobotParams& robot,
                             const std::string& path) {
  double envelope = 0.0;
  for (double torque : robot.envelope.torque) envelope = std::max(envelope, torque);
  const double limit = kMaxTorqueEnvelopeMultiple * envelope;
  for (std::size_t k = 0; k < data.gamma.size(); ++k)
    for (int j = 0; j < 4; ++j)
      if (std::abs(data.gamma[k](j)) > limit)
        throw ConfigError(path, "", 0,
                          "column '" + std::string(kTorque[j]) + "', sample " +
                              std::to_string(k + 1) + " (t = " + formatDouble(data.t[k]) +
                              " s): " + formatDouble(data.gamma[k](j)) + " N m is beyond " +
                              formatDouble(kMaxTorqueEnvelopeMultiple) +
                              " times the robot's largest envelope torque (" +
                              formatDouble(envelope) + " N m)");
}

std::string measuredCsv(const MeasuredData& d) {
  std::ostringstream out;
  CsvRow header;
  header.texts({"t", "alpha", "delta1", "delta2", "delta3", "delta4", "phase", "stance", "step"});
  if (d.has_torque) header.texts({"gamma1", "gamma2", "gamma3", "gamma4"});
  if (d.has_reactions) header.texts({"R1x", "R1z", "R2x", "R2z"});
  if (d.has_cop) header.texts({"cop1x", "cop2x"});
  out << header.line();
  for (std::size_t i = 0; i < d.size(); ++i) {
    CsvRow row;
    row.number(d.t[i]).numbers(d.q[i]).text(d.phase[i] == Phase::SingleSupport ? "SS" : "DS");
    row.text(d.stance[i] == Stance::Left ? "left" : "right").integer(d.step[i]);
    if (d.has_torque) row.numbers(d.gamma[i]);
    if (d.has_reactions) row.numbers(d.reactions[i]);
    if (d.has_cop) row.number(d.cop[i][0]).number(d.cop[i][1]);
    out << row.line();
  }
  return out.str();
}

}  // namespace gaitopt
