#include "gaitopt/opt/initial_guess.hpp"

#include <cmath>

namespace gaitopt {
namespace {

struct LegAngles {
  double alpha, knee;
};

// Stance leg with the foot at the origin and the hip at (x, z): human-like knee (ahead of the
// foot–hip line), tibia angle α from the vertical, knee δ = −π + flexion.
LegAngles legTo(double l_tibia, double l_femur, double x, double z) {
  const double rho2 = x * x + z * z, rho = std::sqrt(rho2);
  const double flexion = M_PI - std::acos((l_tibia * l_tibia + l_femur * l_femur - rho2) /
                                          (2.0 * l_tibia * l_femur));
  const double tibia_to_axis =
      std::acos((l_tibia * l_tibia + rho2 - l_femur * l_femur) / (2.0 * l_tibia * rho));
  return {std::atan2(-x, z) - tibia_to_axis, -M_PI + flexion};
}

}  // namespace

GaitParameters defaultInitialGuess(const Model& m, std::optional<double> speed) {
  const double leg = m.robot.l1 + m.robot.l2;
  const double d = 0.4375 * leg;  // 0.35 m for RABBIT
  const LegAngles start = legTo(m.robot.l1, m.robot.l2, -0.5 * d, 0.9375 * leg);
  const LegAngles end = legTo(m.robot.l1, m.robot.l2, -0.125 * leg, 0.94 * leg);
  const double trunk = 0.5 * M_PI - 0.05;
  // Stance tibia rate −1.44 v / leg length, at least 0.4 rad/s to pass over the stance foot.
  // The factor was measured (0.3–0.85 m/s, factors 1.2 / 1.44 / 1.8): 1.44 reached the lowest
  // optimum at every speed, 1.8 a worse local one at 0.5 and 0.85 m/s.
  const double alphadot = -std::max(0.4, speed.value_or(0.5) * 1.44 / leg);
  GaitParameters p(kNumGaitParameters);
  p << start.alpha, start.knee, trunk, d, end.alpha, end.knee, trunk, end.knee + 0.05, trunk,
      0.0, 0.075 * leg, alphadot, 0.3, 0.3, 0.3, 0.3, 0.12;
  return p;
}

}  // namespace gaitopt
