#pragma once
// Closed-loop walking in gaitopt's own model: single support (stance foot pinned) and double
// support (both feet fixed), touchdown by the phase variable (α = α_fSS) through a touchdown
// map, lift-off at the end of the double support, events located by CVODE's root finding.
//
// Controller (thesis §4.3.1, α replacing time): in SS the four outputs y = δ − δ_d(α) of the
// virtual constraints are driven by input–output linearisation on the controller's model to
// ÿ = −ω² y − 2ω ẏ (critically damped, bandwidth ω); the zero dynamics (α) evolve freely.
// In DS the three free coordinates (α, δ1, δ2) track α_r(t), a cubic from the touchdown state
// to the planned end (α_fDS, α̇_iSS) over T_DS (DS control of α, §4.2.1: it restores the
// cycle's α̇ at lift-off), and δ1,2 = δ_d(α_r(t)); the fourth input R2x is the one of least
// Γ*ᵀΓ* within both friction cones (the 1-D QP (3.68)–(3.70)). Not done: the projection of
// the torques on the torque limits.
#include <functional>
#include <string>
#include <vector>

#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/sim/cvode_integrator.hpp"

namespace gaitopt {

// Maps the state just before touchdown (leg 1 = stance) to the state after it with the legs
// relabelled (leg 1 = new front leg). Returns false with `why` when it cannot.
using TouchdownMap = std::function<bool(const Model& plant, const Vec5& q, const Vec5& qd,
                                        Vec5& q_plus, Vec5& qd_plus, std::string& why)>;

// The touchdown of a gait landing with zero foot velocity: no impulse, only the relabelling
// (3.22), (3.23). Fails ("impact model not available") when the foot speed exceeds `speed_tol`.
TouchdownMap impulseFreeTouchdown(double speed_tol = 1e-6);

struct WalkRequest {
  int steps = 10;
  double bandwidth = 40.0;  // ω [rad/s] of the critically damped output dynamics
  double sample_rate = 200.0;  // trajectory rows [Hz] (events are always recorded)
  double friction_coefficient = 0.8;  // of the DS force split's cones (gait option)
  bool use_initial_state = false;  // start from (q_init, qd_init) instead of the gait's SS start
  Vec5 q_init = Vec5::Zero(), qd_init = Vec5::Zero();
  Vec5 dq0 = Vec5::Zero();     // perturbation of q at the first SS start
  double dalphad0 = 0.0;       // perturbation of α̇ there; q̇ = q*(α) α̇ keeps y, ẏ at 0
  CvodeTolerances tolerances;
};

enum class WalkOutcome {
  Completed,          // every step walked
  ImpactUnavailable,  // touchdown with non-zero foot velocity
  EarlyTouchdown,     // the swing foot went below the ground before α reached α_fSS
  StanceLiftOff,      // a supporting foot's normal force became negative
  Fell,               // α stopped progressing (fell back) or the hip went below 0.3 m
};
const char* outcomeName(WalkOutcome o);

struct WalkSample {
  double t;
  int step;
  bool single_support;
  Vec5 q, qd, qdd;
  Vec4 gamma_star;
  Vec4 output_error;  // y (SS) or (α, δ1, δ2) tracking error and 0 (DS)
  Vec2 R1, R2;
};

struct WalkStep {
  int step;
  double t_start, t_touchdown = 0.0, t_liftoff = 0.0;
  double alphad_start;            // α̇ at SS start
  double max_output_error = 0.0;  // max |y| over SS [rad]
  double touchdown_event_residual = 0.0;  // |α − α_fSS| / |α̇| at the event [s]
  double touchdown_foot_speed = 0.0;
  double energy_start, energy_touchdown = 0.0;     // pinned mechanical energy [J]
  double motor_work = 0.0, friction_loss = 0.0;    // over the SS: ∫ωᵀΓ* dt, ∫ωᵀ(Γ* − Γ) dt
  double min_normal_force = 0.0;                   // over SS and DS, from the samples [N]
};

struct WalkResult {
  WalkOutcome outcome = WalkOutcome::Completed;
  std::string message;
  std::vector<WalkStep> steps;
  std::vector<WalkSample> samples;
  Vec5 q_end = Vec5::Zero(), qd_end = Vec5::Zero();  // state at the last lift-off reached
};

// The closed-loop dynamics at one state: everything the integration, the events and the
// samples need (exposed for the Poincaré sensitivities, sim/poincare_sensitivity.hpp).
struct ClosedLoopEval {
  Vec5 qdd;
  Vec4 gamma_star, error, friction;
  Vec2 R1, R2;
};

// SS when `ds_alpha_reference` is null, else DS tracking that α reference (time t).
ClosedLoopEval evaluateClosedLoop(const GaitMotion<double>& motion, const Model& controller,
                                  const Model& plant, const WalkRequest& request,
                                  const LocalPolynomial<double>* ds_alpha_reference, double t,
                                  const Vec5& q, const Vec5& qd);

// The DS reference α_r(t) from the touchdown state (t, α, α̇) to (α_fDS, α̇_iSS) at t + T_DS.
LocalPolynomial<double> dsAlphaReference(const GaitMotion<double>& motion, double t_touchdown,
                                         double alpha, double alphad);

// `controller` is the model the controller is built on (its friction compensated), `plant` the
// simulated robot; `evaluation` the gait (motion_computed required).
WalkResult simulateWalk(const GaitEvaluation<double>& evaluation, const Model& controller,
                        const Model& plant, const WalkRequest& request,
                        const TouchdownMap& touchdown = impulseFreeTouchdown());

}  // namespace gaitopt
