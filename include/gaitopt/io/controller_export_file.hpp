#pragma once
// Reading back the head of a JSON controller export (`gaitopt export --format json`,
// "gaitopt export"): the embedded gait and robot files, so that a consumer rebuilds the exact
// gait from the export alone, and the cyclic gait and rotor model the feedforward was made with.
//
// Only the keys before the bulky `phases` and `samples` are parsed (yaml-cpp reads JSON), so
// the YAML reader's limits (io/yaml_reader.hpp) apply to that head, whatever the sample count.
#include <string>

#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

// The export format this reader knows (`schema_version` of the JSON).
constexpr int kControllerExportSchema = 2;

struct ControllerExport {
  std::string path;  // the JSON file
  // Robot, parameters, options and model options as the embedded YAML texts say; gait.path is
  // the JSON path and gait.robot_path the robot file the export names (`robot.file`).
  GaitFile gait;
  int schema_version = 0;
  double speed = 0.0, step_length = 0.0, t_ss = 0.0, t_ds = 0.0;  // the cyclic gait's [SI]
  RotorModel rotor = RotorModel::Exact;  // the rotor model of the feedforward
};

// Throws ConfigError naming the file and the key for: a file that is not a controller export
// (no `format: "gaitopt controller export"`), a schema version other than
// kControllerExportSchema, a missing embedded gait or robot, and malformed embedded YAML (then
// the file is named "<path> [gait.yaml]" or "<path> [robot.yaml]" with the key and line inside
// the embedded text).
ControllerExport readControllerExport(const std::string& path);

}  // namespace gaitopt
