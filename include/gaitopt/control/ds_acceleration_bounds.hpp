#pragma once
// Double support on the gait's DS path under perfect tracking of δ1(α), δ2(α) (§4.2.1, H1–H3):
// the admissible interval [α̈_min, α̈_max] of the two 2-variable LPs (4.14) at a state (α, α̇).
//
// On the path q̈ is affine in α̈ (4.3), (4.4); the DS inverse dynamics is affine in (α̈, R2x)
// (4.8), (4.9) and the constraints (4.2) — torque envelope, R_iz ≥ R_min, friction cones with
// f_max — are 14 linear rows in (α̈, R2x) (4.10)–(4.13). The LP is solved exactly by enumerating
// the vertices of that polygon (intersections of pairs of rows; an optimum of a bounded LP in
// the plane is at one): 91 candidate vertices, no iteration, no tolerance on optimality.
#include <Eigen/Core>
#include <limits>

#include "gaitopt/gait/evaluation.hpp"
#include "gaitopt/gait/options.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

// The constants of (4.2); the thesis leaves R_min and f_max open (digest §7.2 gap 6): the gait's
// own min_normal_force and friction coefficient, so that its cyclic DS is admissible.
struct DsLimits {
  double friction_coefficient = 0.8;  // f_max
  double min_normal_force = 20.0;     // R_iz,min [N]
  bool full_torque_envelope = true;   // (3.47) with its sloped parts (thesis: plateau only)
};
DsLimits dsLimitsOf(const GaitOptions& o);

// The DS path at (α, α̇): q = (α, δ1(α), δ2(α), δ3, δ4) with foot 2 on the ground at −d,
// q̇ = T p* α̇ and q̈ = qdd_alphadd α̈ + qdd_bias (4.3), (4.4).
struct DsPathMotion {
  Vec5 q, qd, qdd_alphadd, qdd_bias;
};
DsPathMotion dsPathMotion(const Model& model, const GaitMotion<double>& motion, double alpha,
                          double alphad);

// (4.10)–(4.13): row i gives rows(i, 0) α̈ + rows(i, 1) R2x + rows(i, 2) ≤ 0. Rows 0–3:
// Γ*_j ≤ Γ_max(ω_j); 4–7: −Γ*_j ≤ Γ_max(ω_j); 8: R1z ≥ R_min; 9, 10: R1x ≤ f R1z, −R1x ≤ f R1z;
// 11: R2z ≥ R_min; 12, 13: R2x ≤ f R2z, −R2x ≤ f R2z.
constexpr int kDsConstraintRows = 14;
using DsConstraintRows = Eigen::Matrix<double, kDsConstraintRows, 3>;
DsConstraintRows dsConstraintRows(const Model& model, const DsPathMotion& path,
                                  const DsLimits& limits);
const char* dsConstraintName(int row);  // e.g. "torque_max_2", "R1z_min", "R2_cone_back"

struct DsAccelerationBounds {
  bool defined = false;  // (4.2) feasible at this state (H1)
  double min = std::numeric_limits<double>::quiet_NaN();  // α̈_min [rad/s²]
  double max = std::numeric_limits<double>::quiet_NaN();  // α̈_max
  double r2x_at_min = std::numeric_limits<double>::quiet_NaN();  // R2x of the optimal vertex [N]
  double r2x_at_max = std::numeric_limits<double>::quiet_NaN();
};
// The two LPs (4.14) on the rows; ±∞ when the rows do not bound α̈ on that side.
DsAccelerationBounds solveDsAccelerationLp(const DsConstraintRows& rows);
DsAccelerationBounds dsAccelerationBounds(const Model& model, const GaitMotion<double>& motion,
                                          const DsLimits& limits, double alpha, double alphad);

// The cyclic DS curve of the gait (§4.2.1): α̇_c(α) and its slope dα̇_c/dα (α̈_c = slope α̇ on
// the curve), from the cubic α_c(t) inverted by bisection (α_c is monotone), clamped to the DS.
struct CyclicDsPoint {
  double alphad, slope;
};
CyclicDsPoint cyclicDsAlpha(const GaitMotion<double>& motion, double alpha);

}  // namespace gaitopt
