#pragma once
// Recorded data the identification cannot use (a missing column, no foot on the ground, too
// few samples), located in its file: the column or header key and the 1-based line (0 when
// unknown). The file readers of io/ report it as a ConfigError with the same location.
#include <stdexcept>
#include <string>

namespace gaitopt {

class DataError : public std::runtime_error {
 public:
  // what(): "key '<key>': <problem>", or the problem alone when key is empty.
  DataError(std::string file, std::string key, int line, const std::string& problem);

  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }
  int line() const { return line_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_;
  std::string key_;
  int line_;
  std::string problem_;
};

}  // namespace gaitopt
