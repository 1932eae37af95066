#pragma once
// The stability study of a closed-loop gait (the controller of sim/hybrid_walk.hpp): the
// Poincaré map at SS start linearised on all DOF (variational equations or central
// differences), its eigenvalues and the power iteration (4.61), the 1-D map of the zero
// dynamics' α̇ at SS start (§4.2.2), the DS convergence zone of the time-optimal law (Fig. 4.5)
// and the robustness margins (push, payload, slope).
#include <Eigen/Core>
#include <functional>
#include <string>

#include "gaitopt/sim/ds_convergence_zone.hpp"
#include "gaitopt/sim/poincare.hpp"
#include "gaitopt/sim/stability_margins.hpp"
#include "gaitopt/sim/zero_dynamics_map.hpp"

namespace gaitopt {

// How the Poincaré Jacobian is obtained.
enum class PoincareJacobianMethod { Sensitivity, FiniteDifference };
const char* toString(PoincareJacobianMethod m);  // sensitivity | fd

struct StabilityRequest {
  PoincareJacobianMethod jacobian = PoincareJacobianMethod::Sensitivity;
  double fd_step = 1e-4;    // on every state component (fd Jacobian, power-iteration box)
  int power_iterations = 6;
  double bandwidth = 40.0;  // output bandwidth ω [rad/s]
  DsAlphaControl ds_control = DsAlphaControl::Cubic;
  double map_range = 0.05;  // relative α̇ range of the 1-D map (±)
  int map_points = 51;
  double ds_range = 0.5;    // relative α̇_fDS range of the DS convergence-zone study (±)
  int ds_points = 41;
  int margin_steps = 5;     // steps walked after a push, on a slope or with a payload
  // Called as each of the kStabilityStages stages starts (k = 1…n), for progress reports.
  std::function<void(const std::string& stage, int k, int n)> on_stage;
};

constexpr int kStabilityStages = 6;

struct StabilityMargins {
  MarginRequest request;
  std::string impact_model;  // of the perturbed steps' touchdown
  Margin push_forward, push_backward, trunk_payload, slope_up, slope_down;
};

struct StabilityStudy {
  Eigen::VectorXd fixed_point;  // x = (q, q̇) at SS start on the cycle
  PoincareLinearisation linearisation;
  // The method that gave it: the requested one, or central differences when the variational
  // equations could not be integrated (why in jacobian_fallback).
  PoincareJacobianMethod jacobian_method = PoincareJacobianMethod::Sensitivity;
  std::string jacobian_fallback;
  double power_estimate = 0.0;
  Eigen::VectorXd power_vector;
  double dominant_modulus = 0.0;  // |λ₀|
  bool stable = false;            // |λ₀| < 1
  bool stable_cycle = false;      // stable, and the cycle a fixed point (residual < 1e-6)
  // Samples of one cycle step where the torque projection acts (the analysis itself uses the
  // smooth unsaturated field).
  int saturated_samples_on_cycle = 0;
  ZeroDynamicsStudy zero_dynamics;
  int zero_dynamics_max_steps = 0;
  bool has_double_support = false;  // else no DS zone study
  DsLimits ds_limits;
  DsZoneStudy ds_zone;
  StabilityMargins margins;
};

// `evaluation` is the gait's, with its motion computed; throws std::runtime_error when the
// cycle cannot be walked (the perturbed steps of the maps and margins report how they end).
StabilityStudy studyStability(const GaitEvaluation<double>& evaluation, const RobotParams& robot,
                              const GaitOptions& options, const ModelOptions& model_options,
                              const StabilityRequest& request);

}  // namespace gaitopt
