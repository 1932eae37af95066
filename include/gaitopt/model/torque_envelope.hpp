#pragma once
// Joint-side torque–speed envelope (3.47) of the RS420J motors, piecewise linear in |ω|.
#include "gaitopt/model/robot_params.hpp"
#include "gaitopt/math/scalar.hpp"

namespace gaitopt {

template <class S> S torqueLimit(const TorqueEnvelope& e, const S& speed, bool full) {
  const double w = std::abs(valueOf(speed));
  if (!full || w <= e.speed[0]) return S(e.torque[0]);
  const S abs_speed = valueOf(speed) < 0.0 ? S(-speed) : speed;
  for (std::size_t i = 1; i < e.speed.size(); ++i)
    if (w <= e.speed[i]) {
      const double slope = (e.torque[i] - e.torque[i - 1]) / (e.speed[i] - e.speed[i - 1]);
      return e.torque[i - 1] + slope * (abs_speed - e.speed[i - 1]);
    }
  return S(0.0);
}

}  // namespace gaitopt
