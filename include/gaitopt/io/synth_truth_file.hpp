#pragma once
// The hidden truth `gaitopt synth` writes with its synthetic measurements (ident/synth.hpp): a
// JSON document, put as the comment lines that head the measured-data CSV (io/measured_data.hpp).
#include <string>
#include <vector>

#include "gaitopt/ident/synth.hpp"

namespace gaitopt {

// The hidden truth (effects with values and units, seed, noise, steps) as JSON.
std::string synthTruthJson(const std::string& robot_path, const std::string& gait_path,
                           const std::vector<Effect>& effects, const SynthOptions& options);

}  // namespace gaitopt
