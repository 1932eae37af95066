#pragma once
// The contact check of a closed-loop walk's sample: how far each foot's reaction is inside its
// Coulomb friction cone.
#include "gaitopt/sim/hybrid_walk.hpp"

namespace gaitopt {

// μ R_z − |R_x| of foot 1 and foot 2 [N] at friction coefficient `mu`; foot 2's is 0 in single
// support (the swing foot carries no reaction).
Vec2 frictionConeMargins(const WalkSample& sample, double mu);

}  // namespace gaitopt
