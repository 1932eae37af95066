#pragma once
// Shared file and command helpers for the tests: scratch directories, reading files back,
// documents with some lines replaced, ConfigError expectations and running the gaitopt binary.
#include <catch2/catch.hpp>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "gaitopt/io/config_error.hpp"

namespace gaitopt::test {

// A uniquely named directory under the system temporary directory (gaitopt_<tag>_<random>),
// removed with everything in it when the object is destroyed.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag, std::string default_stem = "file")
      : default_stem_(std::move(default_stem)) {
    std::random_device random;
    dir_ = std::filesystem::temp_directory_path() /
           ("gaitopt_" + tag + "_" + std::to_string(random()));
    std::filesystem::create_directories(dir_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  // Writes `content` to a new file <stem>_<n>.yaml and returns its path.
  std::string write(const std::string& content) { return write(content, default_stem_); }
  std::string write(const std::string& content, const std::string& stem) {
    const std::string path = fresh(stem) + ".yaml";
    std::ofstream(path) << content;
    return path;
  }
  // A new path <stem>_<n> in the directory; nothing is created.
  std::string fresh(const std::string& stem) {
    return (dir_ / (stem + "_" + std::to_string(++count_))).string();
  }
  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
  std::string default_stem_;
  int count_ = 0;
};

inline std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `s` in single quotes, for a shell command line.
inline std::string quoted(const std::string& s) { return "'" + s + "'"; }

// `lines` joined with newlines, some lines (1-based) replaced; "#" blanks a line without
// shifting the others.
inline std::string withLines(const std::vector<std::string>& lines,
                             const std::map<int, std::string>& replaced) {
  std::string text;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto it = replaced.find(static_cast<int>(i + 1));
    text += (it == replaced.end() ? lines[i] : it->second) + "\n";
  }
  return text;
}

// `load(path)` must throw a ConfigError for `key` at `line` of `path`, with the standard
// message (and containing `problem`, unless it is empty).
template <typename Load>
void requireConfigError(Load&& load, const std::string& path, const std::string& key, int line,
                        const std::string& problem = "") {
  try {
    load(path);
    FAIL("no ConfigError; expected key '" << key << "' at line " << line);
  } catch (const ConfigError& e) {
    INFO(e.what());
    CHECK(e.file() == path);
    CHECK(e.key() == key);
    CHECK(e.line() == line);
    const std::string where = path + ":" + std::to_string(line) + ": key '" + key + "': ";
    CHECK_THAT(std::string(e.what()), Catch::Matchers::Contains(where));
    if (!problem.empty()) CHECK_THAT(std::string(e.what()), Catch::Matchers::Contains(problem));
  }
}

struct CliRun {
  int exit_code;
  std::string out, err;
};

// Runs the gaitopt binary with `args` (already quoted for the shell), capturing standard
// output and error in files of a scratch directory of their own.
inline CliRun runCli(const std::string& args) {
  static ScratchDir captured("cli");
  const std::string out = captured.fresh("stdout"), err = captured.fresh("stderr");
  const std::string command =
      quoted(GAITOPT_CLI) + " " + args + " >" + quoted(out) + " 2>" + quoted(err);
  const int status = std::system(command.c_str());
  REQUIRE(WIFEXITED(status));
  return {WEXITSTATUS(status), readFile(out), readFile(err)};
}

}  // namespace gaitopt::test
