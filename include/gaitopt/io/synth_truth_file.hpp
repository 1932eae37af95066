#pragma once
// The truth file `gaitopt synth` writes next to its synthetic measurements (ident/synth.hpp).
#include <string>
#include <vector>

#include "gaitopt/ident/synth.hpp"

namespace gaitopt {

// FILE.truth.json: the hidden truth (effects with values and units, seed, noise, steps).
std::string synthTruthJson(const std::string& robot_path, const std::string& gait_path,
                           const std::vector<Effect>& effects, const SynthOptions& options);

}  // namespace gaitopt
