#pragma once
// The optional `pelvis_frame` section of a robot file lumped from an OpenSim model, read by
// import-opensim for the hip position and the trunk geometry (ident/opensim_import.hpp):
//
//   pelvis_frame:                  # the IK model's pelvis frame, x forward, y up [m, kg]
//     hip: [-0.0724, -0.0677]      # hip joint centre
//     pelvis_com: [-0.0724, 0.0]   # pelvis CoM
//     pelvis_mass: 11.375
//     back: [-0.1032, 0.0835]      # back (lumbar) joint
//     torso_com: [-0.0324, 0.3455] # torso (+ head, arms) CoM in the torso frame
//     torso_mass: 33.068           # pelvis_mass + torso_mass = m3 within 1 %
#include <optional>
#include <string>

#include "gaitopt/ident/opensim_import.hpp"
#include "gaitopt/io/yaml_reader.hpp"

namespace gaitopt {

// The section of the robot document `doc` (none when absent); ConfigError at the key for a
// malformed section or masses that do not make `trunk_mass` (m3).
std::optional<PelvisFrame> readPelvisFrame(const YamlMap& doc, double trunk_mass);

// The section of the robot file `path` (already validated by loadRobot).
std::optional<PelvisFrame> loadPelvisFrame(const std::string& path);

}  // namespace gaitopt
