#include "gaitopt/control/control_constraints.hpp"

#include <array>

#include "gaitopt/gait/constraints/contact.hpp"
#include "gaitopt/gait/constraints/torque_envelope.hpp"

namespace gaitopt {

Eigen::VectorXd controlConstraintRows(const Vec4& gamma_star, const Vec4& limit, const Vec2& R1,
                                      const Vec2& R2, bool double_support, double mu,
                                      double r_min) {
  Eigen::VectorXd c(double_support ? 14 : 11);
  for (int j = 0; j < 4; ++j) {
    const std::array<double, 2> torque = torqueEnvelopeRows(gamma_star(j), limit(j));
    c(j) = torque[0];
    c(4 + j) = torque[1];
  }
  for (int foot = 0; foot < (double_support ? 2 : 1); ++foot) {
    const Vec2& R = foot == 0 ? R1 : R2;
    const std::array<double, 2> cone = frictionConeRows(R, mu);
    c.segment<3>(8 + 3 * foot) << normalForceRow(R, r_min), cone[1], cone[0];
  }
  return c;
}

}  // namespace gaitopt
