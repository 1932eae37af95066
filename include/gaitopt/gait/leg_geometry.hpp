#pragma once
// Closed-chain geometry of the gait: trunk angle (3.17), leg-2 inverse kinematics with the
// human-like knee branch −π < δ4 < 0 ((3.18) corrected, (3.19)), and the leg exchange (3.22).
#include <cmath>

#include "gaitopt/model/model.hpp"
#include "gaitopt/math/scalar.hpp"
#include "gaitopt/math/types.hpp"

namespace gaitopt {

// (3.17): δ2 = α + δ1 − θ3 + π/2.
template <class S> S delta2FromTheta3(const S& alpha, const S& delta1, const S& theta3) {
  return alpha + delta1 - theta3 + 0.5 * M_PI;
}

// Foot 1 relative to the hip, (x1r, z1r) (digest §3.7); −z1r is the hip height.
template <class S> Vector2<S> foot1FromHip(const Model& m, const S& alpha, const S& delta1) {
  using std::cos;
  using std::sin;
  return Vector2<S>(m.robot.l1 * sin(alpha) - m.robot.l2 * sin(alpha + delta1),
                    -m.robot.l1 * cos(alpha) + m.robot.l2 * cos(alpha + delta1));
}

// Leg 2 (δ3, δ4) placing foot 2 at r = foot 2 − hip, knee bent like a human's.
template <class S>
Vector2<S> leg2InverseKinematics(const Model& m, const S& alpha, const S& delta1,
                                 const Vector2<S>& r) {
  using std::acos;
  using std::atan2;
  using std::cos;
  using std::sin;
  const double l4 = m.robot.l4, l5 = m.robot.l5;
  const S rho2 = r.squaredNorm();
  const S delta4 = -acos((l4 * l4 + l5 * l5 - rho2) / (2.0 * l4 * l5));
  const S theta4 = atan2(r(1), r(0)) - atan2(l5 * sin(delta4), l4 - l5 * cos(delta4));
  S delta3 = theta4 - alpha - delta1 - 0.5 * M_PI;
  // Wrap to (−π, π]: a constant shift, so derivatives are untouched.
  delta3 -= 2.0 * M_PI * std::ceil((valueOf(delta3) - M_PI) / (2.0 * M_PI));
  return Vector2<S>(delta3, delta4);
}

// (3.22): the same physical configuration with the legs relabelled (an involution).
template <class S> Vector5<S> exchangeLegs(const Vector5<S>& q) {
  return Vector5<S>(q(0) + q(1) + q(3) - q(4), q(4), q(2) + q(3), -q(3), q(1));
}

// (3.23): velocities under the same relabelling.
template <class S> Vector5<S> exchangeLegVelocities(const Vector5<S>& qd) {
  return exchangeLegs(qd);
}

}  // namespace gaitopt
