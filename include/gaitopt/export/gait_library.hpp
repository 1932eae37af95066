#pragma once
// A gait library over speed in one JSON file (`gaitopt export --library SWEEP_DIR`): the optimal
// gaits of a `gaitopt sweep` output, each with its virtual constraints as polynomials and
// Bézier curves of the normalised phase and its feedforward tables (the `phases` of a
// controller export), one file per robot as in Cassie's gait libraries of Bézier coefficients
// per speed (docs/formats/controller-export.md, "Gait library").
#include <string>
#include <vector>

#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

struct LibraryGait {
  double speed = 0.0;  // as sweep.csv lists it [m/s]
  std::string folder;  // its folder in the sweep output, e.g. "v0.500"
  GaitFile gait;
};

// The gaits that DIR/sweep.csv marks optimal, in increasing speed, read from DIR/<folder>/
// gait.yaml. Throws ConfigError naming sweep.csv (unreadable, malformed, no optimal speed) or
// the gait file.
std::vector<LibraryGait> loadSweepGaits(const std::string& dir);

// The library: `format` "gaitopt gait library", `schema_version`, the robot file embedded once,
// the feedforward's definition (its model: the robot file's friction, `rotor`), the
// conventions, and `gaits`: per speed the speed, folder, the gait file embedded, its cyclic
// gait and its phases. Throws ConfigError naming the gait file when its robot file differs from
// the first gait's (other bytes), its step is undefined or its path is a B-spline.
std::string gaitLibraryJson(const std::vector<LibraryGait>& gaits, RotorModel rotor);

}  // namespace gaitopt
