#pragma once
// Paths of the shipped OpenSim walking trials (data/opensim-subject01-walk/, a treadmill trial
// of the gait10dof18musc pipeline, and data/opensim-rajagopal-walk/, an overground trial of
// another person with a Rajagopal-family model) and helpers to write damaged copies of files.
#include <string>
#include <vector>

#include "test_files.hpp"

namespace gaitopt::test {

inline std::string opensimFile(const std::string& name) {
  return std::string(GAITOPT_SOURCE_DIR) + "/data/opensim-subject01-walk/" + name;
}
inline std::string opensimIk() { return opensimFile("subject01_walk_IK.mot"); }
inline std::string opensimGrf() { return opensimFile("subject01_walk_grf.mot"); }
inline std::string opensimId() { return opensimFile("subject01_walk_ID.sto"); }
inline std::string opensimTrc() { return opensimFile("subject01_walk.trc"); }

inline std::string rajagopalFile(const std::string& name) {
  return std::string(GAITOPT_SOURCE_DIR) + "/data/opensim-rajagopal-walk/" + name;
}
inline std::string rajagopalIk() { return rajagopalFile("coordinates.sto"); }
inline std::string rajagopalGrf() { return rajagopalFile("grf_walk.mot"); }
inline std::string rajagopalId() { return rajagopalFile("id_walk.sto"); }
inline std::string rajagopalTrc() { return rajagopalFile("markers_walk.trc"); }
inline std::string rajagopalModel() { return rajagopalFile("subject_walk_scaled.osim"); }
inline std::string rajagopalRobot() {
  return std::string(GAITOPT_SOURCE_DIR) + "/configs/robot/human_rajagopal_walk.yaml";
}

inline std::vector<std::string> fileLines(const std::string& path) {
  std::vector<std::string> lines;
  std::istringstream in(readFile(path));
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The first `keep` lines of `lines` (all when keep < 0), some (1-based) replaced, written to a
// new file of `dir` with extension `ext`.
inline std::string writeDamaged(ScratchDir& dir, const std::vector<std::string>& lines,
                                const std::map<int, std::string>& replaced, const std::string& ext,
                                int keep = -1) {
  std::vector<std::string> kept(lines.begin(),
                                keep < 0 ? lines.end() : lines.begin() + keep);
  const std::string path = dir.fresh("damaged") + ext;
  std::ofstream(path) << withLines(kept, replaced);
  return path;
}

// `text` with the first occurrence of `from` replaced by `to`.
inline std::string replacedOnce(std::string text, const std::string& from, const std::string& to) {
  return text.replace(text.find(from), from.size(), to);
}

// `load(path)` must throw a ConfigError about the whole row at `line` of `path` (no column),
// whose message contains `problem`.
template <typename Load>
void requireRowError(Load&& load, const std::string& path, int line, const std::string& problem) {
  try {
    load(path);
    FAIL("no ConfigError; expected line " << line);
  } catch (const ConfigError& e) {
    INFO(e.what());
    CHECK(e.file() == path);
    CHECK(e.key().empty());
    CHECK(e.line() == line);
    CHECK_THAT(std::string(e.what()),
               Catch::Matchers::Contains(path + ":" + std::to_string(line) + ": " + problem));
  }
}

}  // namespace gaitopt::test
