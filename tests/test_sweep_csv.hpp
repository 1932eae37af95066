#pragma once
// Rows of sweep.csv texts, for the sweep tests of the library and of the CLI.
#include <sstream>
#include <string>
#include <vector>

namespace gaitopt::test {

// The non-empty lines of `text`.
inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) out.push_back(line);
  return out;
}

// The speed column of a sweep.csv row.
inline double firstField(const std::string& row) { return std::stod(row.substr(0, row.find(','))); }

}  // namespace gaitopt::test
