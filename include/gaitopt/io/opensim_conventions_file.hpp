#pragma once
// What the user and the model file say about an OpenSim trial's conventions
// (ident/opensim_conventions.hpp). The conventions file is a YAML mapping, every key optional:
//
//   plates: {right: ground_force_r_, left: ground_force_l_}   # GRF column prefixes
//   knee_flexion: positive            # sign of knee_angle when the knee bends
//   coordinates: {pelvis_tilt: pelvis_tilt, knee_angle_r: knee_r}  # name here: IK column
//   markers:                          # names separated by blanks
//     pelvis: R.ASIS L.ASIS S2
//     shoulders: R.Shoulder L.Shoulder
//     heels: R.Heel L.Heel            # right, left
#include <string>

#include "gaitopt/ident/opensim_conventions.hpp"

namespace gaitopt {

// ConfigError (file, key, line) for a malformed file or an unknown key.
ConventionHints readConventionsFile(const std::string& path);

// Adds what the OpenSim model `path` (.osim) says: its name, and the knee flexion sign from the
// range of its knee_angle_r coordinate (upper bound above 1 rad: flexion positive, as in the
// Rajagopal family's walker knee; lower bound below −1 rad: negative, as in gait2392 and
// gait10dof18musc). ConfigError when the file is unreadable, has no knee_angle_r range, or
// contradicts a knee sign already in `hints`.
void addModelHints(const std::string& path, ConventionHints& hints);

}  // namespace gaitopt
