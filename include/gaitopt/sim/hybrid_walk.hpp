#pragma once
// Closed-loop walking in gaitopt's own model: single support (stance foot pinned) and double
// support (both feet fixed), touchdown through a touchdown map (impulse-free relabelling, or the
// rigid impact of sim/impact_touchdown.hpp), lift-off at the end of the double support, events
// located by CVODE's root finding. The closed loop itself (controller of §4.3.1, plant, event
// functions) is sim/closed_loop.hpp.
#include <string>
#include <vector>

#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/sim/closed_loop.hpp"
#include "gaitopt/sim/cvode_integrator.hpp"

namespace gaitopt {

struct WalkRequest {
  int steps = 10;
  double bandwidth = 40.0;                   // ω [rad/s] of the critically damped output dynamics
  double gain_scale = 1.0;                   // ControllerOptions::gain_scale
  double sample_rate = 200.0;                // trajectory rows [Hz] (events are always recorded)
  double friction_coefficient = 0.8;         // of the controller's cones (gait option)
  double plant_friction_coefficient = -1.0;  // plant ground μ for slip; < 0: friction_coefficient
  bool detect_slip = true;                   // false: the feet stick whatever the cone (analysis)
  double min_normal_force = 0.0;             // R_min [N] of the projection (gait option)
  double ground_slope = 0.0;                 // plant ground [rad], + uphill (ClosedLoopOptions)
  bool torque_limits = true;                 // project the inputs on the limits (4.57), (4.60)
  bool full_torque_envelope = true;          // (3.47) with its sloped parts (gait option)
  bool touchdown_by_foot_height = false;     // touchdown at foot-2 height 0 (else α = α_fSS)
  bool hold_references_past_fss = false;     // ClosedLoopOptions::hold_references_past_fss
  DsAlphaControl ds_control = DsAlphaControl::Cubic;
  bool use_initial_state = false;  // start from (q_init, qd_init) instead of the gait's SS start
  Vec5 q_init = Vec5::Zero(), qd_init = Vec5::Zero();
  Vec5 dq0 = Vec5::Zero();  // perturbation of q at the first SS start
  double dalphad0 = 0.0;    // perturbation of α̇ there; q̇ = q*(α) α̇ keeps y, ẏ at 0
  CvodeTolerances tolerances;
};

struct WalkSample {
  double t;
  int step;
  bool single_support;
  Vec5 q, qd, qdd;
  Vec4 gamma_star;
  Vec4 output_error;  // y (SS); DS: (α, δ1, δ2) errors (cubic) or (α̇_c − α̇, y1, y2) (time-optimal),
                      // 0
  Vec2 R1, R2;
  bool saturated = false;  // the inputs were projected on the limits
};

struct WalkStep {
  int step;
  double t_start, t_touchdown = 0.0, t_liftoff = 0.0;
  double alphad_start;                    // α̇ at SS start
  double max_output_error = 0.0;          // max |y| over SS [rad]
  double touchdown_event_residual = 0.0;  // |g| / |ġ| of the touchdown event there [s]
  double touchdown_foot_speed = 0.0;
  double touchdown_rise = 0.0;  // world height of the landing foot above the stance foot [m]
  double energy_start, energy_touchdown = 0.0;  // pinned mechanical energy [J]
  double motor_work = 0.0, friction_loss = 0.0;  // over the SS: ∫ωᵀΓ* dt, ∫ωᵀ(Γ* − Γ) dt
  double min_normal_force = 0.0;                 // over SS and DS, from the samples [N]
  // Impact at touchdown (zero and "none" for an impulse-free touchdown).
  std::string impact_behaviour = "none";
  double impact_energy_loss = 0.0;                        // [J]
  Vec2 impulse1 = Vec2::Zero(), impulse2 = Vec2::Zero();  // [N·s]
  bool double_support = true;                             // a DS followed the touchdown
  // Whole step (SS start → next SS start, legs relabelled): ΔE = W − F − impact loss, E_end
  // with the potential measured from the step's stance foot.
  double energy_end = 0.0, step_motor_work = 0.0, step_friction_loss = 0.0;
  int saturated_samples = 0;            // samples where the projection acted
  double first_saturation_time = -1.0;  // [s], −1: none
};

struct WalkResult {
  WalkOutcome outcome = WalkOutcome::Completed;
  std::string message;
  std::vector<WalkStep> steps;
  std::vector<WalkSample> samples;
  Vec5 q_end = Vec5::Zero(), qd_end = Vec5::Zero();  // state at the last lift-off reached
};

// The request's gait-dependent fields from the gait options: the controller's cones and the
// plant's ground (friction_coefficient), the torque envelope, touchdown by foot height, with
// the references held past α_fSS for a zero-velocity landing.
void configureForGait(const GaitOptions& options, WalkRequest& request);

// The closed loop's options of a request (sim/closed_loop.hpp).
ClosedLoopOptions closedLoopOptions(const WalkRequest& request);

// Energy balance of a whole step, relative: (E_end − E_start − (W − F − impact loss)) /
// max(|E_start|, |W|, 1 J); round-off only when the plant's contacts do no work.
double stepEnergyBalanceError(const WalkStep& s);

// `controller` is the model the controller is built on (its friction compensated), `plant` the
// simulated robot; `evaluation` the gait (motion_computed required).
WalkResult simulateWalk(const GaitEvaluation<double>& evaluation, const Model& controller,
                        const Model& plant, const WalkRequest& request,
                        const TouchdownMap& touchdown = impulseFreeTouchdown());

}  // namespace gaitopt
