#pragma once
// The closed-loop walking system as reusable functions of (phase, t, state): the controller of
// §4.3.1 on the controller's model, the plant, the event functions and the touchdown (reset)
// maps. sim/hybrid_walk integrates them with CVODE; the Poincaré analysis (sim/poincare) can
// linearise the same functions.
//
// Controller (α replacing time): in SS the four outputs y = δ − δ_d(α) of the virtual
// constraints are driven by input–output linearisation to ÿ = −ω² y − 2ω ẏ (critically damped,
// bandwidth ω); the zero dynamics (α) evolve freely. In DS either (α, δ1, δ2) track α_r(t), a
// cubic to the planned lift-off state, and δ_d(α_r(t)) (DsAlphaControl::Cubic), or α̈ drives α̇
// to the gait's cyclic curve α̇_c(α) with the outputs δ1,2 − δ_d(α) (TimeOptimal, (4.1)); the
// fourth input R2x is the one of least Γ*ᵀΓ* within both friction cones (the 1-D QP
// (3.68)–(3.70)). The inputs are then projected onto the torque envelope and the contact
// constraints (4.57), (4.60) when they leave them (math/small_qp.hpp).
#include <functional>
#include <string>

#include "gaitopt/gait/evaluation.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

enum class WalkOutcome {
  Completed,          // every step walked
  ImpactUnavailable,  // touchdown the touchdown map cannot resolve (no impact model, or the
                      // impact is inconsistent or indeterminate)
  EarlyTouchdown,     // the swing foot went below the ground before α reached α_fSS
  StanceLiftOff,      // a supporting foot's normal force became negative
  Fell,               // α stopped progressing (fell back) or the hip went below 0.3 m
  Slipped,            // a supporting foot left its friction cone (|Rx| > μ Rz), or slid at impact
  RearFootLift,       // the impact lifted the rear foot of a gait that needs a double support
};
const char* outcomeName(WalkOutcome o);

enum class DsAlphaControl {
  Cubic,        // α_r(t): cubic from the touchdown state to (α_fDS, α̇_iSS) over T_DS
  TimeOptimal,  // (4.1): bang-bang at the exact α̈_min/α̈_max of the LPs (4.14) towards the
                // cyclic curve α̇_c(α), then along it (sim/ds_acceleration_bounds.hpp); ends at α_fDS
};
const char* toString(DsAlphaControl c);  // cubic | time_optimal

// Gain k [1/s] of the time-optimal law (4.1) near the cyclic curve: off the curve by more than
// (α̈_max − α̈_c)/k the demanded α̈ is the exact bound of the LPs (4.14) (bang-bang); within that
// layer it is α̈_c + k (α̇_c − α̇), the regularisation of the switch that an ODE solver needs
// (a discontinuous right-hand side would chatter on the curve).
constexpr double kTimeOptimalGain = 400.0;

struct ClosedLoopOptions {
  double bandwidth = 40.0;                  // ω [rad/s] of the critically damped outputs
  double friction_coefficient = 0.8;        // controller's cones (the gait option)
  double plant_friction_coefficient = 0.8;  // plant ground: slip when |Rx| > μ Rz
  double min_normal_force = 0.0;            // R_min [N] of the projection's normal force rows (4.2)
  // Plant ground inclined by this angle [rad], + uphill (rising toward +x). The state stays in
  // the world frame (gravity vertical, α from the vertical: what the controller measures, so it
  // walks upright on its flat-ground references); foot heights and reactions are taken in the
  // ground frame, the impact is solved there (it does not involve gravity), and the
  // projection's friction cones and normal forces are those of the inclined ground.
  double ground_slope = 0.0;
  bool torque_limits = true;                // project the inputs (4.57), (4.60)
  bool full_torque_envelope = true;         // (3.47) with its sloped parts
  bool touchdown_by_foot_height = false;    // touchdown when foot 2 reaches z = 0 (else α = α_fSS)
  // Past α_fSS the SS references are extrapolated (impact landings) or, with this, held (C¹,
  // their slope decaying over 0.02 rad of α): a zero-velocity landing's foot only grazes the
  // ground at α_fSS and the extrapolated polynomials would lift it again, whereas held outputs
  // turn the robot as one body about the stance foot and bring the swing foot down (the
  // thesis' freeze, §4.3.1.3, made C¹).
  bool hold_references_past_fss = false;
  DsAlphaControl ds_control = DsAlphaControl::Cubic;
};

// The constant parts of one simulation.
struct ClosedLoop {
  const GaitMotion<double>& motion;
  const Model& controller;  // the model the controller is built on (its friction compensated)
  const Model& plant;       // the simulated robot
  ClosedLoopOptions options;
};

// The reference of one double support, set at touchdown.
struct DsReference {
  LocalPolynomial<double> alpha;  // α_r(t) (cubic control)
  double t_start = 0.0, t_end = 0.0;
};
DsReference dsReference(const ClosedLoop& s, double t, const Vec5& q, const Vec5& qd);

// Everything the dynamics, the events and the samples need at one state.
struct ClosedLoopPoint {
  Vec5 qdd = Vec5::Zero();
  Vec4 gamma_star = Vec4::Zero();  // motor torques (controller output, after projection)
  Vec4 friction = Vec4::Zero();    // plant joint friction
  Vec4 error = Vec4::Zero();  // y (SS); DS: (α, δ1, δ2) errors (cubic) or (α̇_c − α̇, y1, y2)
                              // (time-optimal), 0
  Vec2 R1 = Vec2::Zero(), R2 = Vec2::Zero();  // plant reactions, ground frame (x along, z normal)
  bool saturated = false;                     // the projection changed the inputs
  bool projection_infeasible = false;  // contact constraints dropped to keep the torque limits
};
ClosedLoopPoint evaluateClosedLoop(const ClosedLoop& s, bool single_support, const DsReference& ds,
                                   double t, const Vec5& q, const Vec5& qd);

// State y = (q, q̇, ∫ωᵀΓ* dt, ∫ωᵀ(Γ* − Γ) dt): the last two give motor work and friction loss.
constexpr int kClosedLoopStateSize = 12;
void closedLoopRhs(const ClosedLoop& s, bool single_support, const DsReference& ds, double t,
                   const Eigen::VectorXd& y, Eigen::VectorXd& ydot);

// Event functions, an event being a crossing from positive to negative.
constexpr int kClosedLoopEvents = 7;
enum SsEvent {
  kTouchdown,
  kSwingBelowGround,
  kStanceNormal,
  kHipLow,
  kAlphaStalls,
  kStanceSlipForward,
  kStanceSlipBackward
};
enum DsEvent {
  kDsEnd,
  kRearNormal,
  kFrontNormal,
  kRearSlipForward,
  kRearSlipBackward,
  kFrontSlipForward,
  kFrontSlipBackward
};
// A world-frame vector in the plant's ground frame (rotated by −ground_slope).
Vec2 toGroundFrame(const ClosedLoop& s, const Vec2& v);

// The touchdown event alone (kTouchdown): α reaches α_fSS, or (touchdown_by_foot_height) the
// swing foot reaches the ground once α is past mid SS (before, the foot just lifted off may
// graze the ground: the kSwingBelowGround event, 10⁻⁶ m below, ends the walk as
// early_touchdown). Its time derivative at (q, q̇) (for the event residual).
double touchdownEvent(const ClosedLoop& s, const Vec5& q);
double touchdownEventRate(const ClosedLoop& s, const Vec5& q, const Vec5& qd);
void closedLoopEvents(const ClosedLoop& s, bool single_support, const DsReference& ds, double t,
                      const Eigen::VectorXd& y, Eigen::VectorXd& g);

// Touchdown (reset) map: the state just before touchdown (leg 1 = stance) to the state after it
// with the legs relabelled (leg 1 = new front leg).
struct TouchdownResult {
  bool ok = false;
  Vec5 q_plus = Vec5::Zero(), qd_plus = Vec5::Zero();
  bool double_support_follows = true;  // false: foot 1 lifted, the new SS starts at once
  double energy_loss = 0.0;            // kinetic energy dissipated [J]
  Vec2 impulse1 = Vec2::Zero(), impulse2 = Vec2::Zero();  // [N·s], world frame
  std::string behaviour = "none";                         // impact behaviour, e.g. "lift/stick"
  WalkOutcome failure = WalkOutcome::ImpactUnavailable;   // when !ok
  std::string why;                                        // when !ok
};
using TouchdownMap =
    std::function<TouchdownResult(const Model& plant, const Vec5& q, const Vec5& qd)>;

// The touchdown of a gait landing with zero foot velocity: no impulse, only the relabelling
// (3.22), (3.23); a DS follows when `double_support` . Fails ("impact model not available")
// when the foot speed exceeds `speed_tol`.
TouchdownMap impulseFreeTouchdown(double speed_tol = 1e-6, bool double_support = true);

// The touchdown map `map` applied on the plant's inclined ground: solved on the configuration
// rotated into the ground frame (the map assumes flat ground), the result rotated back.
TouchdownResult touchdownOnGround(const ClosedLoop& s, const TouchdownMap& map, const Vec5& q,
                                  const Vec5& qd);

}  // namespace gaitopt
