#pragma once
// Reading a robot description (RobotParams) from a YAML file, with validation of every
// value the dynamics would silently accept but that is non-physical (§1.5, §2.7). The
// schema is documented by the shipped files in configs/robot/.
#include <yaml-cpp/yaml.h>

#include <string>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/model/robot_params.hpp"

namespace gaitopt {

// Throws ConfigError (file, dotted key, line) for unreadable files, schema violations and
// non-physical values. The returned parameters are in SI units and radians; source_file is
// set to `path`.
RobotParams loadRobot(const std::string& path);

// Same, from an already parsed document; `file` is used in messages and as source_file.
RobotParams parseRobot(const YAML::Node& root, const std::string& file);

}  // namespace gaitopt
