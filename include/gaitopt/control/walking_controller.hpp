#pragma once
// The walking controller's law (§4.3.1, α replacing time), a function of the phase, the state
// and the gait: what `gaitopt simulate` integrates against gaitopt's own plant and what the
// reference walker (control/walker.hpp, the C interface control/walker.h) runs on a robot.
//
// Single support: the four outputs y = δ − δ_d(α) of the virtual constraints are driven by
// input–output linearisation on the controller's pinned model to ÿ = −Kp y − Kd ẏ; the zero
// dynamics (α) evolve freely. The outputs are indexed by the phase variable α, not by time, so
// the references' rates use the measured α̇ (ẏ = δ̇ − δ_d'(α) α̇).
// Double support: either (α, δ1, δ2) track α_r(t), a cubic to the planned lift-off state, and
// δ_d(α_r(t)) (DsAlphaControl::Cubic), or α̈ drives α̇ to the gait's cyclic curve α̇_c(α)
// with the outputs δ1,2 − δ_d(α) (TimeOptimal, (4.1)): the speed is regulated at every step.
// The fourth DS input R2x is the one of least Γ*ᵀΓ* within both friction cones (the 1-D QP
// (3.68)–(3.70)). The inputs are projected onto the torque envelope and the contact
// constraints (4.57), (4.60) when they leave them (math/small_qp.hpp).
#include "gaitopt/gait/evaluation.hpp"
#include "gaitopt/gait/polynomials.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

enum class DsAlphaControl {
  Cubic,        // α_r(t): cubic from the touchdown state to (α_fDS, α̇_iSS) over T_DS
  TimeOptimal,  // (4.1): bang-bang at the exact α̈_min/α̈_max of the LPs (4.14) towards the
                // cyclic curve α̇_c(α), then along it (control/ds_acceleration_bounds.hpp);
                // ends at α_fDS
};
const char* toString(DsAlphaControl c);  // cubic | time_optimal

// Gain k [1/s] of the time-optimal law (4.1) near the cyclic curve: off the curve by more than
// (α̈_max − α̈_c)/k the demanded α̈ is the exact bound of the LPs (4.14) (bang-bang); within that
// layer it is α̈_c + k (α̇_c − α̇), the regularisation of the switch that an ODE solver needs
// (a discontinuous right-hand side would chatter on the curve).
constexpr double kTimeOptimalGain = 400.0;

// A reference offset o(t) at the current time, with ȯ and ö.
struct TimedOffset {
  Vec4 value = Vec4::Zero(), rate = Vec4::Zero(), acceleration = Vec4::Zero();
};

struct ControllerOptions {
  // Output gains Kp = gain_scale ω², Kd = gain_scale 2ω: critically damped at gain_scale 1
  // (bandwidth ω [rad/s]); gain_scale scales both (damping ratio √gain_scale).
  double bandwidth = 40.0;
  double gain_scale = 1.0;
  double friction_coefficient = 0.8;  // the projection's friction cones (the gait option)
  double min_normal_force = 0.0;      // R_min [N] of the projection's normal force rows (4.2)
  // Ground inclined by this angle [rad], + uphill: the projection's friction cones and normal
  // forces are those of the inclined ground.
  double ground_slope = 0.0;
  bool torque_limits = true;          // project the inputs (4.57), (4.60)
  bool full_torque_envelope = true;   // (3.47) with its sloped parts
  // Past α_fSS the SS references are extrapolated (impact landings) or, with this, held (C¹,
  // their slope decaying over 0.02 rad of α): a zero-velocity landing's foot only grazes the
  // ground at α_fSS and the extrapolated polynomials would lift it again, whereas held outputs
  // turn the robot as one body about the stance foot and bring the swing foot down (the
  // thesis' freeze, §4.3.1.3, made C¹).
  bool hold_references_past_fss = false;
  DsAlphaControl ds_control = DsAlphaControl::Cubic;
  // Offsets o(t) added to the SS references δ_d(α) and the DS references δ_d1,2(α) (leg-1
  // order) with their time derivatives: the PD tracks them exactly (ẏ and ÿ* carry ȯ and ö),
  // so a step-to-step regulator changes its references smoothly in time, never by a jump of the
  // reference, and also when the phase variable stalls (control/walker.hpp: the trunk lean
  // of the single-support speed regulation).
  TimedOffset timed_offset;
  // Offsets (leg-1 order) reached by the SS references at α_fSS: added to δ_d(α) times the
  // smoothstep 3s² − 2s³ of the phase s (0 at α_iSS, 1 at α_fSS and held past it), so the
  // single support starts on the planned path and ends on the shifted one (control/walker.hpp:
  // the swing foot's end raised or lowered with the ground's slope).
  Vec4 swing_end_offset = Vec4::Zero();
};

struct PdGains {
  double kp, kd;  // [1/s²], [1/s]
};
PdGains pdGains(const ControllerOptions& o);

// The constant parts of the law: the gait, the model the controller is built on (its friction
// compensated) and the options.
struct WalkingController {
  const GaitMotion<double>& motion;
  const Model& controller;
  const ControllerOptions& options;
};

// The reference of one double support, set at touchdown.
struct DsReference {
  LocalPolynomial<double> alpha;  // α_r(t) (cubic control)
  double t_start = 0.0, t_end = 0.0;
  // The DS's target rates (α̇_iSS at lift-off, the cyclic curve α̇_c(α)) times this: the
  // walker's step-to-step speed regulation (control/walker.hpp); 1: the gait's.
  double rate_scale = 1.0;
};
DsReference dsReference(const WalkingController& s, double t, const Vec5& q, const Vec5& qd,
                        double rate_scale = 1.0);

struct ControlOutput {
  Vec4 gamma_star = Vec4::Zero();  // motor torques (after projection), leg-1 joint order
  Vec4 error = Vec4::Zero();  // y (SS); DS: (α, δ1, δ2) errors (cubic) or (α̇_c − α̇, y1, y2)
                              // (time-optimal), 0
  bool saturated = false;     // the projection changed the inputs
  bool projection_infeasible = false;  // contact constraints dropped to keep the torque limits
};

// The law at the state (q, q̇) of the pinned model (leg 1 the stance leg).
ControlOutput singleSupportControl(const WalkingController& s, const Vec5& q, const Vec5& qd);
// A double support whose rear foot (foot 2, leg 1 the front leg) has left the ground: the front
// leg's DS references δ_d1,2(α) kept and foot 2 driven to `target` (pinned frame, foot 1 at the
// origin) by the same input–output linearisation as the single support, with the front foot's
// contact constraints in the projection (control/walker.hpp: the rear foot's re-contact).
ControlOutput recontactControl(const WalkingController& s, const Vec2& target, const Vec5& q,
                               const Vec5& qd);
// The law at the state of the double support (leg 1 the front leg, both feet on the ground).
ControlOutput doubleSupportControl(const WalkingController& s, const DsReference& ds, double t,
                                   const Vec5& q, const Vec5& qd);

}  // namespace gaitopt
