#include "gaitopt/sim/friction_cone_margins.hpp"

#include <cmath>

namespace gaitopt {

Vec2 frictionConeMargins(const WalkSample& s, double mu) {
  return Vec2(mu * s.R1(1) - std::abs(s.R1(0)),
              s.single_support ? 0.0 : mu * s.R2(1) - std::abs(s.R2(0)));
}

}  // namespace gaitopt
