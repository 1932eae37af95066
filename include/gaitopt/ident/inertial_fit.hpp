#pragma once
// The `inertial` candidate of `gaitopt diagnose` (digest seed000_inertial_
// identification.md §1.4, §1.10, §4.4): the link inertial parameters in their linear form,
// the base (identifiable) parameters of a stacked regressor, and a physically consistent
// least-squares fit.
//
// Parameters: per body class, the barycentric triple (m, h = m s, J = I + m s²) about the
// link's proximal joint (the knee for the tibias, the hip for the femurs and the trunk), in
// which the dynamics (1.32), (1.36) are linear. The legs are tied (links 1 and 5 are the
// tibias, 2 and 4 the femurs, and they swap roles every step): a fitted change is added to
// both links of its class. The trunk is the trunk alone (before the bar and any payload are
// folded in by (1.24)), with its CoM at s3 + trunk_com_shift.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "gaitopt/model/robot_params.hpp"

namespace gaitopt {

constexpr int kNumInertialParameters = 9;
// "m_tibia", "h_tibia", "J_tibia", "m_femur", ..., "J_trunk".
extern const std::array<const char*, kNumInertialParameters> kInertialParameterNames;
extern const std::array<const char*, kNumInertialParameters> kInertialParameterUnits;

// The scale of each parameter (1 kg, 0.1 kg·m, 0.1 kg·m²): finite-difference step of the
// regressor columns (exact: the residuals are affine in the parameters) and column scaling.
double inertialScale(int k);

// (m, h, J) of links 1 (tibia), 2 (femur), 3 (trunk) of `robot`.
Eigen::VectorXd inertialParameters(const RobotParams& robot);

// `robot` with `delta` added to the barycentric parameters of every link of each class.
RobotParams withInertialChange(RobotParams robot, const Eigen::VectorXd& delta);

// Base parameters (Gautier: QR with column pivoting of the column-scaled regressor Y S,
// Y P = Q [R1 R2], numerical rank r): the r independent parameters, each absorbing the
// dependent ones, β = p_independent + K p_dependent with K = S_i R1⁻¹ R2 S_d⁻¹.
struct BaseParameters {
  int rank = 0;
  std::vector<int> independent, dependent;
  Eigen::MatrixXd regroup;  // K: rank × dependent
  Eigen::VectorXd values(const Eigen::VectorXd& p) const;
  std::string label(int i) const;  // "J_trunk + 0.31 h_trunk"
};
BaseParameters baseParameters(const Eigen::MatrixXd& Y, double relative_tolerance = 1e-6);

// minimise ‖r0 + Y δ‖² + λ ‖S⁻¹ δ‖² subject to physical consistency of every link of
// `robot` + δ: m > 0, I = J − h²/m > 0 (the planar pseudo-inertia [[J, h], [h, m]] positive
// definite; the triangle inequalities are moot in the plane, the out-of-plane spread being
// free) and the CoM on its link, 0 < s < link length (what a robot file requires). Convex
// (quadratic objective, second-order-cone and linear constraints): primal log-barrier
// interior-point method with damped Newton steps, barrier weight divided by 10 per stage.
// The small λ keeps the directions the data do not excite at the prior (the nominal robot).
struct ConsistentFit {
  Eigen::VectorXd delta;
  // Constraints the unconstrained minimiser violates, which therefore bind the fit
  // ("I_trunk > 0", "s3 < trunk_length", ...): a flag of noise or model inconsistency.
  std::vector<std::string> active;
};
ConsistentFit consistentLeastSquares(const Eigen::MatrixXd& Y, const Eigen::VectorXd& r0,
                                     const RobotParams& robot, double lambda);

}  // namespace gaitopt
