#include "gaitopt/io/tab_text.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace gaitopt {

std::vector<std::string> readTableLines(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw ConfigError(path, "", 0, "cannot open the file");
  const std::streamoff size = in.tellg();
  if (size < 0 || static_cast<std::size_t>(size) > kMaxTableFileBytes) {
    throw ConfigError(path, "", 0,
                      "file larger than the limit of " + std::to_string(kMaxTableFileBytes >> 20) +
                          " MiB");
  }
  in.seekg(0);
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!in.read(&text[0], size)) throw ConfigError(path, "", 0, "cannot read the file");
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

double parseTableNumber(const std::string& field, const std::string& file,
                        const std::string& column, int line_number) {
  if (field.empty()) throw ConfigError(file, column, line_number, "empty value");
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(field.c_str(), &end);
  if (end != field.c_str() + field.size()) {
    throw ConfigError(file, column, line_number, "not a number: '" + field + "'");
  }
  if (errno == ERANGE || !std::isfinite(value)) {
    throw ConfigError(file, column, line_number, "not a finite number: '" + field + "'");
  }
  return value;
}

}  // namespace gaitopt
