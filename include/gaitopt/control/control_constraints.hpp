#pragma once
// The constraint rows of the controllers, c ≤ 0 when satisfied ((4.2), (4.51)–(4.54)), from the
// gait's constraint families (gait/constraints/): the torque envelope (3.46) of the four joints
// (Γ* − Γmax, then −Γ* − Γmax), then for each stance foot its normal force R_min − R_z and its
// friction cone (3.48), R_x − μ R_z then −R_x − μ R_z.
#include <Eigen/Core>

#include "gaitopt/model/model.hpp"

namespace gaitopt {

// 11 rows in SS (foot 1), 14 in DS (foot 2's after foot 1's); reactions in the ground's frame.
Eigen::VectorXd controlConstraintRows(const Vec4& gamma_star, const Vec4& limit, const Vec2& R1,
                                      const Vec2& R2, bool double_support, double mu, double r_min);

}  // namespace gaitopt
