#include "gaitopt/io/tab_text.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "gaitopt/io/input_file.hpp"

namespace gaitopt {

std::vector<std::string> readTableLines(const std::string& path) {
  std::string text =
      readInputFile(path, kMaxTableFileBytes, std::to_string(kMaxTableFileBytes >> 20) + " MiB");
  // A UTF-8 byte order mark (as some spreadsheet programs write) is not part of the header.
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);
  std::vector<std::string> lines;
  std::istringstream stream(text);
  std::string line;
  while (std::getline(stream, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find('\0') != std::string::npos) {
      throw ConfigError(path, "", static_cast<int>(lines.size()) + 1,
                        "binary data (NUL byte) in a text table");
    }
    lines.push_back(line);
  }
  return lines;
}

std::string trimBlanks(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> splitTabFields(const std::string& line, const std::string& file,
                                        int line_number) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t tab = line.find('\t', start);
    fields.push_back(trimBlanks(line.substr(start, tab - start)));
    if (fields.size() > kMaxTableColumns + 1) {
      throw ConfigError(file, "", line_number,
                        "more than " + std::to_string(kMaxTableColumns) + " tab-separated fields");
    }
    if (tab == std::string::npos) break;
    start = tab + 1;
  }
  if (fields.size() > 1 && fields.back().empty()) fields.pop_back();
  return fields;
}

}  // namespace gaitopt
