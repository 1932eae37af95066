#pragma once
// The closed-loop walking system as reusable functions of (phase, t, state): the controller of
// §4.3.1 on the controller's model, the plant, the event functions and the touchdown (reset)
// maps. sim/hybrid_walk integrates them with CVODE; the Poincaré analysis (sim/poincare) can
// linearise the same functions.
//
// The controller is the walking controller's law (control/walking_controller.hpp); this file
// adds the plant (pinned SS, both feet fixed in DS), the events and the touchdown maps.
#include <functional>
#include <string>

#include "gaitopt/control/walking_controller.hpp"
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
  IntegrationFailed,  // CVODE could not integrate the closed loop (its message says why)
};
const char* outcomeName(WalkOutcome o);

// The closed loop's options: the controller's (control/walking_controller.hpp), then the
// plant's.
struct ClosedLoopOptions : ControllerOptions {
  double plant_friction_coefficient = 0.8;  // plant ground: slip when |Rx| > μ Rz
  bool detect_slip = true;                  // false: no slip event (the feet stick)
  bool touchdown_by_foot_height = false;    // touchdown when foot 2 reaches z = 0 (else α = α_fSS)
};

// The constant parts of one simulation.
struct ClosedLoop {
  const GaitMotion<double>& motion;
  const Model& controller;  // the model the controller is built on (its friction compensated)
  const Model& plant;       // the simulated robot
  ClosedLoopOptions options;
};

// The control law of the closed loop.
WalkingController controllerOf(const ClosedLoop& s);
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
