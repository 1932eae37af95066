#pragma once
// Whether a closed-loop walk settled on the gait's cycle.
#include "gaitopt/sim/hybrid_walk.hpp"

namespace gaitopt {

// Converged to a cycle: the walk completed and its last step started on the cycle's α̇
// `alphadot_iSS` (to 1e-6) and repeated the previous step's largest output error (to 1e-6 rad).
bool convergedToCycle(const WalkResult& walk, double alphadot_iSS);

// Tracks the reference: converged with the outputs on the virtual constraints (to 1e-6 rad).
bool tracksReference(const WalkResult& walk, double alphadot_iSS);

}  // namespace gaitopt
