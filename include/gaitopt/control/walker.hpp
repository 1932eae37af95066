#pragma once
// The reference walker: the walking controller's law (control/walking_controller.hpp) run on
// the state a robot measures (trunk pitch, joint-side motor angles, foot contacts), sampled at
// any rate ≥ 500 Hz. It keeps the phase of the walk itself: single support on the leg in
// contact, double support from the swing foot's contact event (not from time or the phase
// variable) until α reaches the gait's lift-off angle (with the rear foot put back on the
// ground when a touchdown on rising ground lifted it), and a fall when the robot leaves the
// region the gait can recover from. The C interface (control/walker.h) wraps this class.
#include <array>

#include "gaitopt/control/apex_energy.hpp"
#include "gaitopt/control/walking_controller.hpp"
#include "gaitopt/gait/evaluation.hpp"
#include "gaitopt/gait/options.hpp"
#include "gaitopt/model/model.hpp"
#include "gaitopt/model/stance.hpp"

namespace gaitopt {

// One measurement, world frame (x forward, z up, angles counter-clockwise), physical joint order
// knee_left, hip_left, hip_right, knee_right (model/stance.hpp).
struct WalkerState {
  double t = 0.0;
  Vec2 hip = Vec2::Zero(), hip_rate = Vec2::Zero();  // the hip joint [m], [m/s]
  double pitch = 0.0, pitch_rate = 0.0;  // trunk from the vertical, > 0 leaning backward
  Vec4 phi = Vec4::Zero(), phi_rate = Vec4::Zero();  // joint-side motor angles φ = D_Γᵀ q
  std::array<bool, 2> contact{false, false};        // left, right foot on the ground
};

struct WalkerOptions : ControllerOptions {
  WalkerOptions() { ds_control = DsAlphaControl::TimeOptimal; }
  double fall_pitch = 1.0;  // |trunk pitch| beyond which the robot is fallen [rad]
  // A phase lasting this many times its planned duration: the phase variable stalled.
  double stall_factor = 4.0;
  double flight_time = 0.1;  // no foot on the ground for this long [s]: fallen
  // The rear foot off the ground for this long [s] ends a double support early: shorter losses
  // are the contact's chatter at the front foot's touchdown.
  double rear_lift_time = 0.02;
  // Time-optimal DS: lift-off past α_fDS once α̇ is within this fraction of its target, or
  // T_DS after the touchdown (walker.cpp).
  double lift_off_rate_tolerance = 0.05;
  // Step-to-step speed regulation: after each step the relative error of its mean speed
  // (stance foot to stance foot over the touchdown period) is summed, and the double support's
  // target rates are scaled by 1 − speed_gain × the sum, within ±max_rate_correction: an
  // integral action that removes the speed offset model errors leave (a rolling foot, the
  // plant's rotor model, a slope, a heavier trunk).
  double speed_gain = 0.2;
  double max_rate_correction = 0.3;
  // Single-support speed regulation (Walker::regulateLean): trunk lean [rad] = lean_gain × the
  // last step's relative speed error + the sum of lean_integral_gain × the errors, within
  // ±max_lean.
  double lean_gain = 0.1;
  double lean_integral_gain = 0.05;
  double max_lean = 0.6;
  // Slope compensation: at each touchdown the ground's inclination γ is measured between the
  // feet, and the next swing foot's end is moved onto the inclined ground (Walker::slopeSwingEnd:
  // raised uphill at the planned step length, lowered and kDownhillShortening shorter
  // downhill). Downhill the trunk also leans back by −slope_compensation × (z_c / ∂x_c/∂pitch)
  // γ, added to the regulation's lean; uphill a rear foot the touchdown lifted is put back on
  // the ground (Walker::switchPhase). A slope within ±slope_deadband [rad] is level ground.
  double slope_compensation = 1.0;
  double slope_deadband = 0.005;
  // Single-support energy (control/apex_energy.hpp): the gait's zero dynamics predict from the
  // angular momentum about the stance foot the squared momentum σ_apex² with which the robot
  // will pass over it. The double support does not end while the single support it starts
  // would pass with less than apex_energy_fraction of the gait's own σ_apex²; its rate
  // correction never targets a start rate below that; the lean back of the regulation stays
  // within what the start leaves above it (Walker::maxBackLean).
  double apex_energy_fraction = 0.5;
};

// The controller options a gait asks for: its friction cones, normal-force margin and torque
// envelope in the projection, references held past α_fSS for a zero-velocity landing.
// The normal force the walker keeps on each supporting foot in its model is at least
// kWalkerNormalForceFraction of the robot's weight: the planned double support may load the rear
// foot with only the gait's min_normal_force (20 N on the shipped gaits), and the plant's model
// errors (rotor model, compliant contact, rolling foot) then lift it, which leaves the double
// support without the foot it regulates the speed with. Measured in MuJoCo on the default gait:
// 0.3 keeps the rear foot down at gain_scale 0.5, 20 N does not.
constexpr double kWalkerNormalForceFraction = 0.3;

// The longest double support [planned durations] the walker holds for the single support's
// energy (WalkerOptions::apex_energy_fraction): below the fall judgement's stall_factor.
constexpr double kMaxDsExtension = 3.0;

// Rear-foot re-contact (Walker::switchPhase): the target lies this far [m] below the point where
// the foot left the ground, so the PD brings it down at a small speed instead of stopping short
// of the ground; the re-contact is given up after kRecontactTime [s] (a single support follows).
// Measured on 0.035 rad uphill: with 2 mm the 0.75 m/s C&A gait stalls at its first step, with
// 5 mm the default gait walks 3.3 % slow; with 3 mm the 0.5, 0.8 and C&A 0.75 m/s gaits walk
// within 1.1 % of their speed.
constexpr double kRecontactDepth = 0.003;
constexpr double kRecontactTime = 0.15;

// Downhill step shortening (Walker::slopeSwingEnd): the fraction of the planned step length
// the swing foot lands short on ground sloping down. Measured in MuJoCo on 0.035 rad downhill
// (100 steps, the seven shipped gaits): all walk with 0.16 to 0.18; 0.15 loses the 0.5 m/s
// impact gait (stalls), 0.19 and 0.2 the 0.3 m/s gait (−5.2 % at 0.2), 0.1 the impact gaits
// of Chessé and the default robot; on 0.02 and 0.01 rad all 7 walk with 0.17 (the lift-off
// energy counted additively in the rate bound), 5 of 7 without shortening or lowering. Proportional to the slope (8 |γ|, at most 0.17) walked 4 of 7 on
// 0.02 rad: the gaits' speed regulation is sensitive to the step length changing with each
// touchdown's slope measurement.
constexpr double kDownhillShortening = 0.17;

// The trunk lean of the speed regulation (Walker::regulateLean) moves from the previous step's
// to the new one over this fraction of the gait's T_SS after the touchdown.
constexpr double kLeanBlend = 0.3;
WalkerOptions walkerOptionsFor(const GaitOptions& gait, const Model& model);

// The walker's view of the walk.
enum class WalkerPhase { SingleSupport, DoubleSupport, Fallen };

struct WalkerCommand {
  Vec4 tau = Vec4::Zero();  // joint-side motor torques Γ*, physical order
  bool fallen = false;
  ControlOutput law;  // the law's output (leg-1 order)
};

class Walker {
 public:
  // `model`: the controller's model of the robot (its friction compensated); `gait` an evaluated
  // gait (motion_computed). Throws std::invalid_argument when the gait has no motion.
  Walker(Model model, GaitEvaluation<double> gait, const Parameterisation& parameterisation,
         WalkerOptions options);

  // The first sample of a single support on the left leg, stance foot at rest at x = 0, t = 0.
  WalkerState initialState() const;
  const GaitEvaluation<double>& gait() const { return gait_; }
  const Model& model() const { return model_; }

  WalkerCommand torques(const WalkerState& s);
  WalkerPhase phase() const { return phase_; }
  Stance leg1() const { return leg1_; }
  int steps() const { return steps_; }  // touchdowns so far

 private:
  Model model_;
  GaitEvaluation<double> gait_;
  bool double_support_ = true;  // a double support follows each touchdown
  WalkerOptions options_;
  WalkerPhase phase_ = WalkerPhase::SingleSupport;
  Stance leg1_ = Stance::Left;  // the stance leg in SS, the front leg in DS
  bool started_ = false;
  double phase_start_ = 0.0;
  double last_contact_ = 0.0;  // time of the last sample with a foot on the ground
  double rear_contact_ = 0.0;  // in DS: time of the last sample with the rear foot on the ground
  double stance_x_ = 0.0, stance_t_ = 0.0;  // stance foot x [m] and its touchdown time [s]
  double speed_error_sum_ = 0.0;             // Σ (step speed / gait speed − 1)
  int steps_ = 0;
  DsReference ds_;
  // In DS: the rear foot is being put back on the ground (recontactControl) at rear_target_
  // (pinned frame of the front foot); at most once per double support.
  bool recontact_ = false, recontacted_ = false;
  double recontact_start_ = 0.0;
  Vec2 rear_target_ = Vec2::Zero();
  double liftoff_energy_excess_ = 0.0;  // σ² [(kg m²/s)²]
  void measureLiftOffEnergy(const Vec5& q, const Vec5& qd);  // at lift-off: liftoff_energy_excess_

  WalkingController law() const { return {gait_.motion, model_, options_}; }
  double phaseProgress(double alpha) const;  // s of the SS: 0 at α_iSS, 1 at α_fSS
  void switchPhase(const WalkerState& s);
  bool fallen(const WalkerState& s, const Vec5& q) const;
  double stanceFootX(const WalkerState& s) const;  // world x of leg 1's foot
  Stance startingLeg(const WalkerState& s) const;  // leg 1 at the first sample
  double stepSpeedError(const WalkerState& s);  // at a touchdown: the last step's speed error
  double rateScale(double error);               // after a touchdown: the DS's rate scale
  double lowestRateScale() const;               // the rate scale's lower bound
  // After a touchdown: the trunk lean, from the step's speed error, the DS's rate scale and the
  // apex energy σ_apex² predicted from the touchdown state.
  void regulateLean(double error, double scale, double t, double touchdown_energy);
  double lean_from_ = 0.0, lean_to_ = 0.0, lean_start_ = 0.0;   // its blend in time
  PolyValue<double> leanAt(double t) const;  // the lean [rad] and its time derivatives at t
  double maxBackLean(double rate_scale, double touchdown_energy) const;
  double start_alpha_ = 0.0;  // α at which the next single support starts (set at touchdowns)
  double lean_torque_ = 0.0;  // M g ∂x_c/∂pitch: gravity's torque per radian of lean [N·m]
  double lean_integral_ = 0.0;
  double slope_ = 0.0;             // the ground's inclination measured at the last touchdown
  double slope_lean_ratio_ = 0.0;  // trunk lean per radian of slope (walker.cpp)
  double slopeLean() const;
  Vec4 slopeSwingEnd() const;  // the swing foot's end offsets for slope_
  ApexEnergy apex_;
  double apexRatio(const Vec5& q, const Vec5& qd) const;  // σ_apex² from (q, q̇) / the gait's
  TimedOffset referenceOffset(double t) const;            // the law's timed offset at t
};

// Pinned coordinates q = (α, δ1..δ4) and rates of the measured state with `leg1` as leg 1
// ((1.13): pitch = α + δ1 − δ2, φ = (δ1, −δ2, −(δ2 + δ3), δ4) in leg-1 order).
void pinnedStateOf(const WalkerState& s, Stance leg1, Vec5& q, Vec5& qd);

// The ground's inclination [rad], + uphill, between the feet of the pinned configuration q
// (α absolute, both feet on the ground): the direction from foot 1 to foot 2. The walker
// measures it at each touchdown.
double groundSlopeBetweenFeet(const Model& model, const Vec5& q);

// The offsets (leg-1 order, on the swing leg's δ3, δ4) that move the swing foot's end of the
// gait's single support (q_fSS) onto ground inclined by `slope` (+ uphill) through the stance
// foot, at (1 − shortening) times the planned step length (ControllerOptions::swing_end_offset;
// the walker sets it from the slope measured at each touchdown, Walker::slopeSwingEnd).
Vec4 slopeSwingOffset(const Model& model, const GaitMotion<double>& motion, double slope,
                      double shortening = 0.0);

// Leg-1 joint order (knee 1, hip 1, hip 2, knee 2) ↔ physical order: an involution.
Vec4 physicalOrder(const Vec4& leg_order, Stance leg1);

}  // namespace gaitopt
