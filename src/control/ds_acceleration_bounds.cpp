#include "gaitopt/control/ds_acceleration_bounds.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "gaitopt/gait/boundary_geometry.hpp"
#include "gaitopt/gait/constraints/torque_envelope.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"
#include "gaitopt/control/control_constraints.hpp"

namespace gaitopt {
namespace {

// Box closing the LP polygon so that it always has vertices; an optimum on it means the rows
// leave α̈ unbounded on that side (reported as ±∞).
constexpr double kAlphaddBox = 1e6;  // [rad/s²]
constexpr double kR2xBox = 1e7;      // [N]
// A vertex satisfies a row when a x + b y + c ≤ kFeasibleTolerance (|a x| + |b y| + |c|): the
// round-off of the 2×2 solve, far below any physical margin.
constexpr double kFeasibleTolerance = 1e-12;

// The 14 constraint values at (α̈, R2x), c ≤ 0 meaning satisfied; affine in (α̈, R2x).
Eigen::Matrix<double, kDsConstraintRows, 1> constraintValues(const Model& m, const DsPathMotion& p,
                                                             const DsLimits& l, double alphadd,
                                                             double r2x) {
  const Vec5 qdd = p.qdd_alphadd * alphadd + p.qdd_bias;
  const DoubleSupportInverseDynamics<double> id =
      inverseDynamicsDS(m, p.q, p.qd, qdd, r2x, SignMode::Smooth);  // (4.8), (4.9)
  const Vec4 limit = jointTorqueLimits(m.robot.envelope, jointSpeeds(p.qd), l.full_torque_envelope);
  return controlConstraintRows(id.gamma_star, limit, id.R1, id.R2, true, l.friction_coefficient,
                               l.min_normal_force);  // (4.2)
}

bool satisfies(double a, double b, double c, double x, double y) {
  return a * x + b * y + c <=
         kFeasibleTolerance * (std::abs(a * x) + std::abs(b * y) + std::abs(c));
}

}  // namespace

DsLimits dsLimitsOf(const GaitOptions& o) {
  return {o.friction_coefficient, o.min_normal_force, o.full_torque_envelope};
}

DsPathMotion dsPathMotion(const Model& m, const GaitMotion<double>& mo, double alpha,
                          double alphad) {
  const PolyValue<double> d1 = mo.ds_delta1(alpha), d2 = mo.ds_delta2(alpha);
  const Vec2 leg2 =
      leg2InverseKinematics(m, alpha, d1.value, rearFootFromHip(m, alpha, d1.value, mo.d));
  DsPathMotion p;
  p.q << alpha, d1.value, d2.value, leg2;
  const Matrix25<double> D2 = chainPointJacobian(m, m.pinned.foot2, chainState(m, p.q, Vec5(Vec5::Zero())));
  const Eigen::Matrix2d D245_inv = D2.rightCols<2>().inverse();
  Vec5 Tps;  // T p*: ∂q/∂α along the path (4.3)
  Tps.head<3>() << 1.0, d1.first, d2.first;
  Tps.tail<2>() = -D245_inv * D2.leftCols<3>() * Tps.head<3>();
  p.qd = Tps * alphad;
  const Vec2 H2 = chainPointBias(m.pinned.foot2, chainState(m, p.q, p.qd));
  Vec5 Tpss;  // T p** α̇² + [0; −D245⁻¹ H2] (4.4)
  Tpss.head<3>() << 0.0, d1.second * alphad * alphad, d2.second * alphad * alphad;
  Tpss.tail<2>() = -D245_inv * (D2.leftCols<3>() * Tpss.head<3>() + H2);
  p.qdd_alphadd = Tps;
  p.qdd_bias = Tpss;
  return p;
}

DsConstraintRows dsConstraintRows(const Model& m, const DsPathMotion& p, const DsLimits& l) {
  // Exact columns: the constraint values are affine in (α̈, R2x) (4.10).
  const auto c0 = constraintValues(m, p, l, 0.0, 0.0);
  DsConstraintRows rows;
  rows.col(0) = constraintValues(m, p, l, 1.0, 0.0) - c0;
  rows.col(1) = constraintValues(m, p, l, 0.0, 1.0) - c0;
  rows.col(2) = c0;
  return rows;
}

const char* dsConstraintName(int row) {
  static const char* const names[kDsConstraintRows] = {
      "torque_max_1", "torque_max_2", "torque_max_3", "torque_max_4", "torque_min_1",
      "torque_min_2", "torque_min_3", "torque_min_4", "R1z_min",      "R1_cone_front",
      "R1_cone_back", "R2z_min",      "R2_cone_front", "R2_cone_back"};
  return row >= 0 && row < kDsConstraintRows ? names[row] : "unknown";
}

DsAccelerationBounds solveDsAccelerationLp(const DsConstraintRows& rows) {
  Eigen::Matrix<double, kDsConstraintRows + 4, 3> r;
  r.topRows<kDsConstraintRows>() = rows;
  r.bottomRows<4>() << 1, 0, -kAlphaddBox, -1, 0, -kAlphaddBox, 0, 1, -kR2xBox, 0, -1, -kR2xBox;
  DsAccelerationBounds b;
  const int n = static_cast<int>(r.rows());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const double det = r(i, 0) * r(j, 1) - r(j, 0) * r(i, 1);
      if (std::abs(det) <= 1e-14 * (std::abs(r(i, 0) * r(j, 1)) + std::abs(r(j, 0) * r(i, 1))))
        continue;  // parallel rows: no vertex
      const double x = (-r(i, 2) * r(j, 1) + r(j, 2) * r(i, 1)) / det;
      const double y = (-r(i, 0) * r(j, 2) + r(j, 0) * r(i, 2)) / det;
      bool feasible = true;
      for (int k = 0; k < n && feasible; ++k) feasible = satisfies(r(k, 0), r(k, 1), r(k, 2), x, y);
      if (!feasible) continue;
      if (!b.defined || x < b.min) b.min = x, b.r2x_at_min = y;
      if (!b.defined || x > b.max) b.max = x, b.r2x_at_max = y;
      b.defined = true;
    }
  const double inf = std::numeric_limits<double>::infinity();
  if (b.defined && b.max >= kAlphaddBox * (1.0 - 1e-12)) b.max = inf;
  if (b.defined && b.min <= -kAlphaddBox * (1.0 - 1e-12)) b.min = -inf;
  return b;
}

DsAccelerationBounds dsAccelerationBounds(const Model& m, const GaitMotion<double>& mo,
                                          const DsLimits& l, double alpha, double alphad) {
  return solveDsAccelerationLp(dsConstraintRows(m, dsPathMotion(m, mo, alpha, alphad), l));
}

CyclicDsPoint cyclicDsAlpha(const GaitMotion<double>& mo, double alpha) {
  double lo = 0.0, hi = mo.T_DS;
  const bool decreasing = mo.ds_alpha(hi).value < mo.ds_alpha(lo).value;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    ((mo.ds_alpha(mid).value > alpha) == decreasing ? lo : hi) = mid;
  }
  const PolyValue<double> a = mo.ds_alpha(0.5 * (lo + hi));
  return {a.first, a.second / a.first};  // dα̇/dα = α̈(t) / α̇(t)
}

}  // namespace gaitopt
