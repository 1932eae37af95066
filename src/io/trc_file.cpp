#include "gaitopt/io/trc_file.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/tab_text.hpp"
#include "gaitopt/io/yaml_reader.hpp"

namespace gaitopt {

namespace {

constexpr int kHeaderLines = 5;

struct TrcHeader {
  double rate = 0.0, unit = 1.0;
  long frames = 0, markers = 0;
};

long positiveCount(const std::map<std::string, std::string>& values, const std::string& key,
                   const std::string& file) {
  const auto it = values.find(key);
  if (it == values.end()) throw ConfigError(file, key, 3, "missing from the header");
  const double v = parseCsvNumber(it->second, file, key, 3);
  if (v < 1 || v > 1e12 || v != std::floor(v)) {
    throw ConfigError(file, key, 3, "must be a positive integer, got '" + it->second + "'");
  }
  return static_cast<long>(v);
}

TrcHeader readHeader(const std::vector<std::string>& lines, const std::string& file) {
  if (lines.size() < kHeaderLines) {
    throw ConfigError(file, "", static_cast<int>(lines.size()), "truncated .trc header");
  }
  if (lines[0].rfind("PathFileType", 0) != 0) {
    throw ConfigError(file, "", 1, "not a .trc file: the first line must start with PathFileType");
  }
  const std::vector<std::string> names = splitTabFields(lines[1], file, 2);
  std::vector<std::string> values = splitTabFields(lines[2], file, 3);
  // Some writers pad the values line with empty fields (`100.0\t\t100.0\t\t238`); OpenSim
  // reads the non-empty ones in order.
  if (names.size() != values.size())
    values.erase(std::remove(values.begin(), values.end(), std::string()), values.end());
  if (names.size() != values.size()) {
    throw ConfigError(file, "", 3,
                      std::to_string(values.size()) + " non-empty header values for " +
                          std::to_string(names.size()) + " header names on line 2");
  }
  std::map<std::string, std::string> header;
  for (std::size_t k = 0; k < names.size(); ++k) header[names[k]] = values[k];
  TrcHeader h;
  const auto rate = header.find("DataRate");
  if (rate == header.end()) throw ConfigError(file, "DataRate", 3, "missing from the header");
  h.rate = parseCsvNumber(rate->second, file, "DataRate", 3);
  if (!(h.rate > 0.0)) throw ConfigError(file, "DataRate", 3, "must be > 0");
  h.frames = positiveCount(header, "NumFrames", file);
  h.markers = positiveCount(header, "NumMarkers", file);
  const auto units = header.find("Units");
  if (units == header.end() || (units->second != "mm" && units->second != "m")) {
    throw ConfigError(file, "Units", 3, "must be 'mm' or 'm'");
  }
  h.unit = units->second == "mm" ? 1e-3 : 1.0;
  return h;
}

std::vector<std::string> markerNames(const std::string& line, const std::string& file,
                                     long expected) {
  const std::vector<std::string> fields = splitTabFields(line, file, 4);
  if (fields.size() < 2 || fields[0] != "Frame#" || fields[1] != "Time") {
    throw ConfigError(file, "", 4, "the marker-name row must start with 'Frame#' and 'Time'");
  }
  std::vector<std::string> names;
  for (std::size_t k = 2; k < fields.size(); ++k)
    if (!fields[k].empty()) names.push_back(fields[k]);
  if (static_cast<long>(names.size()) != expected) {
    throw ConfigError(file, "NumMarkers", 4,
                      "header says " + std::to_string(expected) + " markers, the name row has " +
                          std::to_string(names.size()));
  }
  return names;
}

}  // namespace

TrcData readTrcFile(const std::string& path) {
  const std::vector<std::string> lines = readTableLines(path);
  const TrcHeader h = readHeader(lines, path);
  TrcData trc;
  trc.file = path;
  trc.rate = h.rate;
  trc.markers = markerNames(lines[3], path, h.markers);
  const std::size_t n_fields = 2 + 3 * trc.markers.size();
  // Sized by the lines there are, not by NumFrames alone: a header claiming 10^12 frames must
  // end as a truncated file, not as a terabyte allocation (found by fuzz_trc_file).
  const long capacity = std::min<long>(h.frames, static_cast<long>(lines.size()) - kHeaderLines);
  trc.time.resize(capacity);
  trc.positions.resize(capacity, static_cast<Eigen::Index>(3 * trc.markers.size()));
  long frame = 0;
  int last_line = kHeaderLines;
  for (std::size_t i = kHeaderLines; i < lines.size(); ++i) {
    const int line = static_cast<int>(i) + 1;
    if (trimBlanks(lines[i]).empty()) continue;
    if (frame == h.frames) {
      throw ConfigError(path, "NumFrames", line, "more frames than NumFrames=" + std::to_string(h.frames));
    }
    const std::vector<std::string> fields = splitTabFields(lines[i], path, line);
    if (fields.size() != n_fields) {
      throw ConfigError(path, "", line,
                        "row has " + std::to_string(fields.size()) + " fields, expected " +
                            std::to_string(n_fields) + " (Frame#, Time, X/Y/Z of " +
                            std::to_string(trc.markers.size()) + " markers)");
    }
    trc.time(frame) = parseCsvNumber(fields[1], path, "Time", line);
    if (frame > 0 && !(trc.time(frame) > trc.time(frame - 1))) {
      throw ConfigError(path, "Time", line, "time does not increase strictly");
    }
    for (std::size_t c = 2; c < n_fields; ++c) {
      const std::string column = trc.markers[(c - 2) / 3] + "." + "XYZ"[(c - 2) % 3];
      const double x = h.unit * parseCsvNumber(fields[c], path, column, line);
      if (std::abs(x) > kMaxMarkerDistance)
        throw ConfigError(path, column, line,
                          printable(fields[c]) + " " + (h.unit == 1.0 ? "m" : "mm") +
                              " lies beyond " + showNumber(kMaxMarkerDistance) +
                              " m of the origin: check the header's Units (millimetres "
                              "declared as m?)");
      trc.positions(frame, static_cast<Eigen::Index>(c - 2)) = x;
    }
    ++frame;
    last_line = line;
  }
  if (frame != h.frames) {
    throw ConfigError(path, "NumFrames", last_line,
                      "the file has " + std::to_string(frame) + " frames but its header says NumFrames=" +
                          std::to_string(h.frames) + " (truncated file)");
  }
  if (frame > 0 && trc.positions.cwiseAbs().maxCoeff() < kMinMarkerSpread)
    throw ConfigError(path, "Units", 3,
                      "every marker lies within " + showNumber(kMinMarkerSpread) +
                          " m of the origin: check the header's Units (metres declared as mm?)");
  return trc;
}

}  // namespace gaitopt
