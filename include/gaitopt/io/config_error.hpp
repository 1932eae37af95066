#pragma once
// Error in a user-supplied configuration file (robot, gait or optimiser YAML). It names the
// file, the offending key as a dotted path and its line, so the user can fix the file without
// reading the code; the CLI turns it into exit code 2.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace gaitopt {

// `text` safe to print on a terminal: control characters, DEL and bytes that are not valid
// UTF-8 become \xNN escapes, and text longer than `max_bytes` is cut with "...". Every message
// that echoes user input goes through it (messages name the file, key and value as written).
std::string printable(const std::string& text, std::size_t max_bytes = 200);

class ConfigError : public std::runtime_error {
 public:
  // Message: "<file>:<line>: key '<key>': <problem>", file and key made printable. The
  // ":<line>" part is left out when
  // line is 0 (unknown), and the "key '<key>': " part when key is empty (file-level errors
  // such as an unreadable or unparsable file).
  ConfigError(std::string file, std::string key, int line, const std::string& problem);

  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }  // dotted path, e.g. "masses.m3"
  int line() const { return line_; }               // 1-based, 0 if unknown
  const std::string& problem() const { return problem_; }

 private:
  std::string file_;
  std::string key_;
  int line_;
  std::string problem_;
};

}  // namespace gaitopt
