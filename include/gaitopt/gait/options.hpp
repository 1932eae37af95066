#pragma once
#include "gaitopt/gait/parameters.hpp"
// Options of a gait evaluation: the choices the thesis leaves open (digest §6), each with a
// documented default.
namespace gaitopt {

enum class DsDistribution {
  Torque,  // pointwise min Γ*ᵀΓ* (3.60), (3.68)–(3.70)
  Energy,  // pointwise min electrical power (3.61), (3.71)–(3.75)
};

// Highest walking speed accepted anywhere (options.target_speed, the config's speed, --speeds,
// sweep.csv) [m/s]: RABBIT-class robots walk at about 1 m/s; 10 m/s leaves room for any biped
// of this kind while refusing values whose arithmetic would overflow.
constexpr double kMaxWalkingSpeed = 10.0;

struct GaitOptions {
  Parameterisation parameterisation;  // thesis: 17 parameters
  double friction_coefficient = 0.8;  // ground f (gap #1: Ch. 2 calls 1 a rarely exceeded value)
  double clearance_height = 0.03;     // z_max of the clearance parabola (3.49) [m] (gap #2)
  double min_normal_force = 20.0;     // R_iz ≥ 20 N, Fig. 3.11 caption (gap #3)
  // Include the robot's Coulomb friction Γs (smooth sign, model/joint_friction.hpp) in Γ*, as
  // the exported feedforward does: the torque envelope then holds for the torque the motors
  // are asked for. false: viscous friction only (the §3.6 results); the feasibility verdict
  // still checks the envelope with the robot's whole friction (gait/feasibility.hpp).
  bool dry_friction = true;
  DsDistribution ds_distribution = DsDistribution::Torque;
  double sample_rate = 1000.0;        // trajectory.csv rate [Hz]
  // Semi-infinite constraints and quadratures use Chebyshev–Lobatto grids of n+1 points
  // (spectral accuracy on the smooth phase integrands).
  int ss_nodes = 32;
  int ds_nodes = 16;
  // W and C_E integrate |Γ*_j ω_j| and max(0, P) split at their roots, i.e. the interpolant
  // of those integrands between the nodes: in the SS they are sampled on a grid this many
  // times finer (nested in the SS grid; 1: the SS grid), which takes them from ~10⁻⁹ to ~10⁻¹⁵
  // relative on the shipped optima. C_Γ, C_frott and the constraints keep the SS grid.
  int criteria_refinement = 2;
  // Margins that turn the thesis' strict inequalities into ≤ (gap #4).
  double f_min = 1.0;                 // f(α) ≥ f_min [kg·m²], also the saturation (3.54)
  double alphadot_margin = 0.05;      // ε of (3.56) [rad/s]
  double ds_alphadot_max = -0.01;     // DS monotonicity α̇ ≤ this (3.43) [rad/s]
  double angle_margin = 1e-3;         // α orderings (3.38), (3.40) [rad]
  // Minimum DS range α_iDS − α_fDS [rad] of (3.38): the DS polynomials δ(α) are fitted over
  // this range, and a vanishing one makes their slopes (and the torques) overflow.
  double ds_alpha_range_min = 0.02;
  double reach_margin = 1e-4;         // hip–foot distance² away from 0 and (l4+l5)² [m²]
  double kappa_min = 0.1;             // leg-exchange factor κ (gap #9)
  double joint_limit_margin = 0.0;    // on (3.39), (3.42) [rad]
  bool full_torque_envelope = true;   // (3.47) with its sloped parts, not only the 140 N·m plateau
  double target_speed = 0.0;          // > 0: report the speed constraint (3.50) [m/s]
  // > 0 (landing: impact only): the swing foot reaches the ground moving down at least this
  // fast [m/s], so that a vertical tracking error Δz moves touchdown by at most Δz / this
  // (gait/constraints/touchdown_speed.hpp).
  double touchdown_speed_min = 0.0;
};

}  // namespace gaitopt
