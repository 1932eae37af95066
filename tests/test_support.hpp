#pragma once
// Shared fixtures for the tests: the shipped robots and seeded random states.
#include <cstdlib>
#include <random>
#include <string>

#include "gaitopt/model/model.hpp"
#include "gaitopt/io/robot_file.hpp"

namespace gaitopt::test {

// True when GAITOPT_TEST_LIGHT is set (not "0"): the sanitizer run of scripts/test.sh, about
// ten times slower, runs the slow optimisation tests in a lighter form (fewer starts).
inline bool lightTests() {
  const char* v = std::getenv("GAITOPT_TEST_LIGHT");
  return v != nullptr && *v != '\0' && std::string(v) != "0";
}

inline std::string sourcePath(const std::string& relative) {
  return std::string(GAITOPT_SOURCE_DIR) + "/" + relative;
}

inline RobotParams robotFile(const std::string& name) {
  return loadRobot(sourcePath("configs/robot/" + name + ".yaml"));
}

inline Model defaultModel(const ModelOptions& options = {}) {
  return buildModel(robotFile("rabbit_miossec"), options);
}

// Walking-like random configurations: knees flexed, trunk near upright, moderate speeds.
struct RandomStates {
  std::mt19937 rng{12345};
  Vec5 q() {
    std::uniform_real_distribution<double> u(-0.4, 0.4);
    return Vec5(u(rng), -M_PI + 0.3 + u(rng) * 0.5, -M_PI + u(rng), u(rng) * 1.5,
                -M_PI + 0.3 + u(rng) * 0.5);
  }
  Vec5 qd() {
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    return Vec5(u(rng), u(rng), u(rng), u(rng), u(rng));
  }
};

}  // namespace gaitopt::test
