#pragma once
// Constant, evaluation-independent description of the dynamic model (Pinocchio's `Model`):
// body parameters with the support bar folded into the trunk (1.24), the map q → θ of the
// absolute body angles (1.13), and the constant coefficient matrices of the planar chain.
// Per-evaluation quantities are computed by the free functions of dynamics_*.hpp.
#include <Eigen/Core>

#include "gaitopt/model/robot_params.hpp"

namespace gaitopt {

using Vec2 = Eigen::Matrix<double, 2, 1>;
using Vec4 = Eigen::Matrix<double, 4, 1>;
using Vec5 = Eigen::Matrix<double, 5, 1>;
using Mat5 = Eigen::Matrix<double, 5, 5>;

enum class RotorModel {
  Exact,     // (1.17): rotor speed = carrier body speed ± N × joint speed
  HighGear,  // (A.1): rotor speed ≈ N × joint speed only (Appendix A comparison)
};

struct ModelOptions {
  RotorModel rotor = RotorModel::Exact;
  // Width ε [rad/s] of the smooth sign tanh(ω/ε) used for Coulomb friction in optimisation.
  // 0.05 rad/s: below 3 % of typical walking joint speeds, wide enough to keep the
  // torque–parameter map's curvature moderate for the NLP solver.
  double friction_smoothing = 0.05;
};

// A point or centre of mass written as origin + Σ_k coeff(k) u(θ_k), u(θ) = (cos θ, sin θ).
// Inertia of the chain in θ-coordinates: M_θ(k,l) = P(k,l) cos(θ_k − θ_l) + δ_kl I_k,
// potential g Σ_k b(k) sin θ_k (digest §2.2 recipe, specialised to a planar serial chain).
struct ChainCoefficients {
  Mat5 P;           // Σ_i m_i c_ik c_il
  Vec5 b;           // Σ_i m_i c_ik  (first mass moments)
  Mat5 body;        // row i: coefficients of CoM of body i
  Vec5 foot1, foot2, hip;
};

struct Model {
  RobotParams robot;
  ModelOptions options;
  Vec5 mass;         // m1..m5 with the bar in m3* (1.24)
  Vec5 com_offset;   // s1..s5 with s3* (1.24)
  Vec5 inertia;      // I_y1..I_y5 with I_y3* (1.24)
  double total_mass = 0.0;
  Mat5 theta_map;    // T in θ = T q + theta_offset (1.13)
  Mat5 theta_map_transpose;
  Vec5 theta_offset;
  ChainCoefficients pinned;    // origin at foot 1 (1.37), (1.38)
  ChainCoefficients floating;  // origin at the trunk CoM (1.14), (1.15)
  Mat5 rotor_inertia_matrix;   // Σ_j I_mj w_j w_jᵀ, constant (1.17)
  Eigen::Matrix<double, 5, 4> D_Gamma;  // (1.19)
  Vec4 coulomb, viscous;
  double gravity = 9.81;
};

Model buildModel(const RobotParams& robot, const ModelOptions& options = {});

// Joule-loss coefficient R/(N K_em)² [W/(N·m)²] on joint-side torques: the printed R/K_em²
// of (3.32) mixes a motor-side constant with joint-side torques (digest gap #5).
inline double jouleCoefficient(const Model& m) {
  const double nk = m.robot.gear_ratio * m.robot.motor_torque_constant;
  return m.robot.motor_resistance / (nk * nk);
}

}  // namespace gaitopt
