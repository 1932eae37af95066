#pragma once
// Line-level reading of tab-separated numeric text files (OpenSim .mot/.sto, .trc, CSV-like
// exports). Every problem becomes a ConfigError naming the file, the column and the 1-based
// line, so that a truncated or hand-edited recording is diagnosed without reading code.
#include <cstddef>
#include <string>
#include <vector>

#include "gaitopt/io/config_error.hpp"

namespace gaitopt {

// Resource limits of the tabular readers: a larger file is refused before it is parsed
// (a 2.5 s trial at 600 Hz is 0.2 MB; 64 MiB is ~10 min of 41 markers at 120 Hz).
constexpr std::size_t kMaxTableFileBytes = std::size_t{64} << 20;
constexpr std::size_t kMaxTableColumns = 4096;

// All lines of `path` (without line ends; a trailing '\r' is dropped). Throws ConfigError
// when the file is missing, unreadable, larger than kMaxTableFileBytes or contains a NUL.
std::vector<std::string> readTableLines(const std::string& path);

// `text` without leading and trailing blanks (spaces, tabs).
std::string trimBlanks(const std::string& text);

// Fields of one tab-separated line, each trimmed of spaces. One trailing empty field (a line
// that ends with a tab, as OpenSim writes them) is dropped. Throws ConfigError (file, line)
// when the line has more than kMaxTableColumns fields.
std::vector<std::string> splitTabFields(const std::string& line, const std::string& file,
                                        int line_number);

}  // namespace gaitopt
