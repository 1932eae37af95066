#pragma once
// A double-support configuration typed by hand (or printed with a few decimals) puts foot 2 a
// few micrometres off the ground, where an impact (ch. 2) is not defined. The closest
// configuration with foot 2 on it: Newton steps of minimum norm on z2(q) = 0 (1.38), which
// change q by about |z2| / |∂z2/∂q| and keep foot 1 at the origin.
#include "gaitopt/model/model.hpp"

namespace gaitopt {

struct GroundProjection {
  Vec5 q;                    // foot 2 on the ground: |z2| ≤ kGroundProjectionTolerance
  double height = 0.0;       // z2 of the configuration given [m]
  double max_change = 0.0;   // max_i |Δq_i| [rad]
  bool converged = false;
};

constexpr double kGroundProjectionTolerance = 1e-12;  // [m]

GroundProjection projectFoot2OnGround(const Model& model, const Vec5& q);

}  // namespace gaitopt
