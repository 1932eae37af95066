#pragma once
// Optimiser configuration files, as read by `gaitopt optimize` (and reused by commands that run
// many optimisations, e.g. a speed sweep). Schema (every key is described in docs/formats/optimizer-config.md,
// section "gaitopt optimize"):
//
//   robot: robot/rabbit_miossec.yaml   # required; relative to this file's directory
//   options: {...}                     # optional gait options (parseGaitOptions), no target_speed
//   criterion: C_Gamma                 # optional: C_Gamma (default) | C_E | W
//   speed: 0.5                         # optional [m/s], > 0; absent: free speed
//   parameterisation: miossec          # optional; the only one that exists
//   initial_guess: default             # optional: default | a gait file (relative to this file)
//   solver:                            # optional, every key optional
//     backend: nlopt_slsqp             # nlopt_slsqp (default) | ipopt | nlopt_cobyla
//     hierarchy: staged                # staged (default) | direct
//     max_iter: 500                    # integer >= 1
//     tol: 1.0e-8                      # > 0
//     constraint_exchange: true
//     print_every: 1                   # integer >= 0 (0: no progress lines)
//     ipopt: {key: value, ...}         # backend ipopt only; checked against Ipopt at load time
//
// Reading is as strict as for robot and gait files: every problem is a ConfigError naming the
// file, the dotted key and its line.
#include <optional>
#include <string>
#include <vector>

#include "gaitopt/opt/optimizer.hpp"
#include "gaitopt/gait/options.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/opt/gait_problem.hpp"
#include "gaitopt/model/model.hpp"
#include "gaitopt/model/robot_params.hpp"
#include "gaitopt/io/overrides.hpp"

namespace gaitopt {

struct OptimizeConfig {
  std::string path;        // the configuration file, as given
  std::string robot_path;  // the robot file, resolved relative to the config file's directory
  RobotParams robot;
  // Gait options; options.target_speed is set from `speed` (0 when the speed is free), so the
  // evaluation reports speed_error and a written gait file records the target.
  GaitOptions options;
  ModelOptions model_options;
  Criterion criterion = Criterion::Torque;
  std::optional<double> speed;  // m/s, > 0; empty: free speed
  std::string parameterisation = "miossec";
  // Gait file of the starting point, resolved relative to the config file's directory; empty
  // for `initial_guess: default` (defaultInitialGuess of the robot at `speed`).
  std::optional<std::string> initial_guess_path;
  GaitParameters initial_guess_parameters;  // filled for a gait file
  Parameterisation initial_guess_parameterisation;  // that file's
  SolverSettings solver;  // defaults of SolverSettings for every absent key
  std::vector<std::string> overrides;  // the command line's KEY=VALUE, recorded in summary.json
};

// Throws ConfigError for an unreadable or malformed file, a missing `robot`, an unknown or
// misspelt key at any depth, a value of the wrong type, an unknown criterion, backend,
// hierarchy or parameterisation, speed <= 0, max_iter < 1 (or not an integer), tol <= 0,
// print_every < 0, an Ipopt option that Ipopt rejects (reported at `solver.ipopt.<key>`), an
// unavailable Ipopt linear_solver, an output_file that is not a plain file name,
// option_file_name, Ipopt options with an NLopt backend,
// `options.target_speed` (use `speed`), and a missing or unreadable robot or initial-guess
// gait file (reported at the config's `robot` / `initial_guess` key; errors inside those
// files name the files themselves). Only the parameters of an initial-guess gait file are
// used (refined if coarser; a richer one is an error); its robot and options are ignored.
OptimizeConfig loadOptimizeConfig(const std::string& path);
// The same with the command line's overrides applied to the document first.
OptimizeConfig loadOptimizeConfigWithOverrides(const std::string& path,
                                               const std::vector<Override>& overrides);

// Points the Ipopt option output_file (a plain file name, checked at load) into `dir`, the
// directory the run writes, so that a configuration cannot write anywhere else.
void placeIpoptOutputFile(SolverSettings& solver, const std::string& dir);

// The configured starting point: the gait file's parameters, or defaultInitialGuess(model,
// config.speed) for `initial_guess: default`.
GaitParameters configuredInitialGuess(const OptimizeConfig& config, const Model& model);

// The optimisation request of the configuration, starting at `initial`.
OptimizationRequest optimizationRequest(const OptimizeConfig& config,
                                        const GaitParameters& initial);

}  // namespace gaitopt
