#pragma once
// Gait files: one walking step (the parameters of gait/parameters.hpp), the robot it is
// for and the evaluation options, as read by `gaitopt evaluate` and written by the optimiser.
//
//   robot: ../robot/rabbit_miossec.yaml   # relative to the gait file's directory
//   parameterisation: {ss_points: 3, ds_points: 1}   # optional; default the thesis' 17
//   parameters: {alpha_iDS: ..., ..., T_DS: ...}   # all of them, radians / metres / seconds
//   options: {...}                        # optional, every key optional (docs/formats/gait-file.md)
//
// Reading is as strict as for robot files: every problem is a ConfigError naming the file,
// the dotted key and its line.
#include <string>
#include <vector>

#include "gaitopt/gait/options.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/model/model.hpp"
#include "gaitopt/model/robot_params.hpp"
#include "gaitopt/io/overrides.hpp"
#include "gaitopt/io/yaml_reader.hpp"

namespace gaitopt {

struct GaitFile {
  std::string path;        // the gait file, as given
  std::string robot_path;  // the robot file, resolved relative to the gait file's directory
  RobotParams robot;
  GaitParameters parameters;
  GaitOptions options;
  ModelOptions model_options;
  std::vector<std::string> overrides;  // the command line's KEY=VALUE (io/overrides.hpp)
};

// Throws ConfigError for an unreadable or malformed gait file, a missing, unknown or
// non-numeric parameter, d ≤ 0 or T_DS ≤ 0, a bad option, and a missing or unreadable robot
// file (reported at the gait file's `robot` key). Errors inside the robot file itself are
// reported by loadRobot, naming the robot file.
GaitFile loadGaitFile(const std::string& path);
// The same with the command line's overrides applied to the document first.
GaitFile loadGaitFileWithOverrides(const std::string& path, const std::vector<Override>& overrides);

// Everything of a parsed gait document but the robot, with the checks of loadGaitFile: `path`
// is doc.file(), `robot_path` the `robot` key resolved against its directory (not checked for
// existence), `robot` left default for the caller to load.
GaitFile parseGaitDocument(const YamlMap& doc);

// The `parameterisation` key of `doc`: absent or "miossec" (the thesis' 17 parameters), or a
// mapping {ss_points: odd ≥ 1, ds_points: ≥ 0, basis: polynomial|bspline} of interior SS/DS
// configurations and the curve through them (gait/path_curve.hpp); `landing`
// comes from the options (`landing: impact`, `after_impact: single_support|double_support`).
Parameterisation parseParameterisation(const YamlMap& doc,
                                       Landing landing = Landing::ZeroVelocity);

// The parameters of `parameters_map`, named by `par.names()` (each required, plain finite
// numbers; d and T_DS > 0). Unknown keys are rejected.
GaitParameters parseGaitParameters(const YamlMap& parameters_map,
                                   const Parameterisation& par = {});

// Gait options of an `options:` mapping (every key optional; defaults are those of GaitOptions
// and ModelOptions). `rotor` and `friction_smoothing` go to `model_options`, which is
// otherwise left as passed in. Values are range-checked; unknown keys are rejected, so the map
// must hold gait options only.
GaitOptions parseGaitOptions(const YamlMap& options_map, ModelOptions& model_options);

// YAML text of the `options:` mapping body: every option, one `key: value` line each,
// indented by `indent` spaces, full precision. parseGaitOptions reads it back identically.
std::string gaitOptionsYaml(const GaitOptions& options, const ModelOptions& model_options,
                            int indent = 2);

// A complete gait file (header comment, robot path, every parameter in order at full
// precision, every option) that loadGaitFile reads back with bit-identical values.
// `robot_path_relative` is written as given; it is resolved against the directory the
// file is saved in.
std::string gaitYaml(const std::string& robot_path_relative, const GaitParameters& parameters,
                     const GaitOptions& options, const ModelOptions& model_options);

}  // namespace gaitopt
