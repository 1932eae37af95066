#include "gaitopt/io/opensim_table.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/tab_text.hpp"

namespace gaitopt {

namespace {

struct HeaderEntry {
  std::string value;
  int line;
};

struct Header {
  std::map<std::string, HeaderEntry> entries;  // key=value lines
  int end_line = 0;                            // 1-based line of `endheader`
};

Header readHeader(const std::vector<std::string>& lines, const std::string& file) {
  Header header;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string line = trimBlanks(lines[i]);
    if (line == "endheader") {
      header.end_line = static_cast<int>(i) + 1;
      return header;
    }
    // `key=value` (version 1 and later); the old SIMM-style header writes `datarows 1501`.
    auto eq = line.find('=');
    if (eq == std::string::npos && (line.rfind("datarows ", 0) == 0 || line.rfind("datacolumns ", 0) == 0))
      eq = line.find(' ');
    if (eq != std::string::npos) {
      header.entries[trimBlanks(line.substr(0, eq))] = {trimBlanks(line.substr(eq + 1)),
                                                        static_cast<int>(i) + 1};
    }
  }
  throw ConfigError(file, "", static_cast<int>(lines.size()),
                    "no 'endheader' line: not an OpenSim .mot/.sto file, or truncated header");
}

// The inDegrees flag; absent in files that hold no angles (a GRF .mot written by some tools,
// the old SIMM-style header with datacolumns/datarows), where it is not needed.
std::optional<bool> inDegreesFlag(const Header& header, const std::string& file) {
  const auto it = header.entries.find("inDegrees");
  if (it == header.entries.end()) return std::nullopt;
  if (it->second.value != "yes" && it->second.value != "no") {
    throw ConfigError(file, "inDegrees", it->second.line,
                      "must be 'yes' or 'no', got '" + it->second.value + "'");
  }
  return it->second.value == "yes";
}

struct HeaderCount {
  long value;
  std::string key;
};

// The header's count under `key` or its old-header synonym (datarows), if any.
std::optional<HeaderCount> headerCount(const Header& header, const std::string& key,
                                       const std::string& old_key, const std::string& file) {
  auto it = header.entries.find(key);
  if (it == header.entries.end()) it = header.entries.find(old_key);
  if (it == header.entries.end()) return std::nullopt;
  const double v = parseCsvNumber(it->second.value, file, it->first, it->second.line);
  if (v < 0 || v > 1e12 || v != std::floor(v)) {
    throw ConfigError(file, it->first, it->second.line, "must be a non-negative integer");
  }
  return HeaderCount{static_cast<long>(v), it->first};
}

std::vector<std::string> columnNames(const std::vector<std::string>& fields,
                                     const std::string& file, int line) {
  if (fields.empty() || fields[0] != "time") {
    throw ConfigError(file, fields.empty() ? "" : fields[0], line,
                      "the column-name row must start with 'time'");
  }
  std::set<std::string> seen;
  for (const std::string& name : fields) {
    if (name.empty()) throw ConfigError(file, "", line, "empty column name");
    if (!seen.insert(name).second) throw ConfigError(file, name, line, "duplicate column name");
  }
  return fields;
}

}  // namespace

OpenSimTable readOpenSimTable(const std::string& path) {
  const std::vector<std::string> lines = readTableLines(path);
  const Header header = readHeader(lines, path);
  OpenSimTable table;
  table.file = path;
  const std::optional<bool> degrees = inDegreesFlag(header, path);
  table.in_degrees = degrees.value_or(false);
  table.units_declared = degrees.has_value();
  std::size_t i = static_cast<std::size_t>(header.end_line);
  while (i < lines.size() && trimBlanks(lines[i]).empty()) ++i;
  if (i == lines.size()) throw ConfigError(path, "", static_cast<int>(i), "no column-name row");
  table.columns = columnNames(splitTabFields(lines[i], path, int(i) + 1), path, int(i) + 1);
  // nColumns is not checked: OpenSim reads the name row, and the RRA-adjusted IK .sto it
  // writes declares more columns (its states) than it holds; every row is checked against the
  // name row instead.
  std::vector<double> data;
  table.first_data_line = static_cast<int>(i) + 2;
  std::size_t n_rows = 0;
  int last_line = static_cast<int>(i) + 1;
  for (++i; i < lines.size(); ++i) {
    const int line = static_cast<int>(i) + 1;
    if (trimBlanks(lines[i]).empty()) continue;
    if (last_line != line - 1) throw ConfigError(path, "", line - 1, "blank line inside the data");
    last_line = line;
    const std::vector<std::string> fields = splitTabFields(lines[i], path, line);
    if (fields.size() != table.columns.size()) {
      throw ConfigError(path, "", line,
                        "row has " + std::to_string(fields.size()) + " fields, expected " +
                            std::to_string(table.columns.size()) + " (one per column)");
    }
    for (std::size_t c = 0; c < fields.size(); ++c) {
      data.push_back(parseCsvNumber(fields[c], path, table.columns[c], line));
    }
    const std::size_t at = data.size() - fields.size();
    if (n_rows > 0 && !(data[at] > data[at - fields.size()])) {
      throw ConfigError(path, "time", line, "time does not increase strictly");
    }
    ++n_rows;
  }
  if (const auto n = headerCount(header, "nRows", "datarows", path);
      n && n->value != static_cast<long>(n_rows)) {
    throw ConfigError(path, "", last_line,
                      "the file has " + std::to_string(n_rows) + " data rows but its header says " +
                          n->key + "=" + std::to_string(n->value) + " (truncated or edited file)");
  }
  if (n_rows < 2) throw ConfigError(path, "", last_line, "fewer than 2 data rows");
  table.values = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic,
                                                Eigen::RowMajor>>(
      data.data(), static_cast<Eigen::Index>(n_rows),
      static_cast<Eigen::Index>(table.columns.size()));
  return table;
}

}  // namespace gaitopt
