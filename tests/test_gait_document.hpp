#pragma once
// A valid gait document with the shipped robot, line by line, for the tests that edit single
// lines of it (the reader's error messages, the CLI's exit codes).
#include <map>
#include <string>
#include <vector>

#include "test_files.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

// A valid gait document; the numbers on the right are the 1-based line numbers that the
// error tests assert. Line 2 is filled in with the absolute path of the default robot.
inline std::vector<std::string> validGait() {
  const std::string robot = sourcePath("configs/robot/rabbit_miossec.yaml");
  return {
      "# written by test_gait_io.cpp",  // 1
      "robot: " + robot,                // 2
      "parameters:",                    // 3
      "  alpha_iDS: -0.044819",         // 4
      "  delta1_iDS: -2.593492",        // 5
      "  theta3_iDS: 1.520796",         // 6
      "  d: 0.35",                      // 7
      "  alpha_fDS: -0.190837",         // 8
      "  delta1_fDS: -2.495513",        // 9
      "  theta3_fDS: 1.520796",         // 10
      "  delta1_int: -2.445513",        // 11
      "  theta3_int: 1.520796",         // 12
      "  x2r_int: 0.0",                 // 13
      "  z2_int: 0.06",                 // 14
      "  alphadot_iSS: -0.9",           // 15
      "  delta1s_iSS: 0.3",             // 16
      "  delta2s_iSS: 0.3",             // 17
      "  delta1s_fSS: 0.3",             // 18
      "  delta2s_fSS: 0.3",             // 19
      "  T_DS: 0.12",                   // 20
      "options:",                       // 21
      "  sample_rate: 1000",            // 22
      "  ds_distribution: torque",      // 23
      "  ss_nodes: 32",                 // 24
  };
}

// The valid gait with some lines (1-based) replaced; "#" blanks a line without shifting others.
inline std::string gaitWith(const std::map<int, std::string>& replaced = {}) {
  return withLines(validGait(), replaced);
}

}  // namespace gaitopt::test
