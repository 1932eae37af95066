#pragma once
// The robot file (docs/formats/robot-file.md) of a five-link lumping of an OpenSim model
// (ident/osim_lumping.hpp), with a provenance comment naming the model file, its SHA-256,
// which bodies went into which link and what the lumping dropped.
#include <string>

#include "gaitopt/ident/osim_lumping.hpp"

namespace gaitopt {

// YAML text readable by loadRobot; numbers at 6 significant digits.
std::string lumpedRobotYaml(const OsimLumping& lumping, const std::string& name,
                            const std::string& model_path, const std::string& model_sha256);

}  // namespace gaitopt
