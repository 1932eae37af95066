#pragma once
// A valid optimiser configuration with the shipped robot, line by line, for the tests that
// edit single lines of it (the library's error messages, the CLI's exit codes).
#include <map>
#include <string>
#include <vector>

#include "test_files.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

// The numbers on the right are the 1-based lines the error tests assert.
inline std::vector<std::string> validConfig() {
  return {
      "# written by test_optimize.cpp",                                 // 1
      "robot: " + sourcePath("configs/robot/rabbit_miossec.yaml"),      // 2
      "options:",                                                       // 3
      "  ss_nodes: 32",                                                 // 4
      "criterion: C_Gamma",                                             // 5
      "speed: 0.5",                                                     // 6
      "parameterisation: miossec",                                      // 7
      "initial_guess: default",                                         // 8
      "solver:",                                                        // 9
      "  backend: ipopt",                                               // 10
      "  hierarchy: staged",                                            // 11
      "  max_iter: 500",                                                // 12
      "  tol: 1.0e-8",                                                  // 13
      "  constraint_exchange: false",                                   // 14
      "  print_every: 0",                                               // 15
      "  ipopt:",                                                       // 16
      "    limited_memory_max_history: 30",                             // 17
      "    mu_strategy: adaptive",                                      // 18
  };
}

// The valid configuration with some lines (1-based) replaced; "#" blanks a line.
inline std::string configWith(const std::map<int, std::string>& replaced = {}) {
  return withLines(validConfig(), replaced);
}

}  // namespace gaitopt::test
