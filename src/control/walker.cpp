#include "gaitopt/control/walker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "gaitopt/gait/constraints/torque_envelope.hpp"
#include "gaitopt/model/chain_kinematics.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/joint_friction.hpp"

namespace gaitopt {
namespace {

int side(Stance s) { return s == Stance::Left ? 0 : 1; }
Stance other(Stance s) { return s == Stance::Left ? Stance::Right : Stance::Left; }

// A phase past this fraction of its α range: a contact of the swing foot is its touchdown
// (before, the foot just lifted off may still touch the ground).
constexpr double kTouchdownArmed = 0.5;

// How a trunk lean moves the centre of mass at the gait's mid single support, on the
// controller's model: its height z_c and ∂x_c/∂pitch (pitch = α + δ1 − δ2: ∂/∂pitch = −∂/∂δ2
// with α, δ1, δ3, δ4 kept).
struct LeanLever {
  double height, shift;  // z_c [m], ∂x_c/∂pitch [m/rad]
};
LeanLever leanLever(const Model& model, const GaitMotion<double>& mo) {
  Vec5 q;
  q(0) = 0.5 * (mo.q_iSS(0) + mo.alpha_fSS);
  for (int j = 0; j < 4; ++j) q(j + 1) = mo.ss_path[j](q(0)).value;
  const Vec5 zero = Vec5::Zero();
  constexpr double h = 1e-6;
  const Vec2 com = pinnedTerms(model, q, zero).com;
  const double x_back = pinnedTerms(model, Vec5(q + h * Vec5::Unit(2)), zero).com(0);
  return {com(1), (com(0) - x_back) / h};
}

// The trunk lean [rad] per radian of ground slope that keeps the centre of mass's horizontal
// offset from the stance foot, and so the gravity torque that drives the zero dynamics, at its
// planned value: the slope turns the step's geometry by γ about the stance foot, which moves the
// centre of mass forward by z_c γ downhill; the lean moves it by ∂x_c/∂pitch per radian.
double slopeLeanRatio(const LeanLever& l) {
  return -l.height / l.shift;  // lean = ratio × (−γ): back downhill
}

}  // namespace

Vec4 physicalOrder(const Vec4& v, Stance leg1) {
  return leg1 == Stance::Left ? v : Vec4(v.reverse());
}

void pinnedStateOf(const WalkerState& s, Stance leg1, Vec5& q, Vec5& qd) {
  const auto pinned = [](double pitch, const Vec4& phi) {
    const double d1 = phi(0), d2 = -phi(1);
    return Vec5(pitch - d1 + d2, d1, d2, phi(1) - phi(2), phi(3));
  };
  q = pinned(s.pitch, physicalOrder(s.phi, leg1));
  qd = pinned(s.pitch_rate, physicalOrder(s.phi_rate, leg1));
}

WalkerOptions walkerOptionsFor(const GaitOptions& g, const Model& m) {
  WalkerOptions o;
  o.friction_coefficient = g.friction_coefficient;
  o.min_normal_force =
      std::max(g.min_normal_force, kWalkerNormalForceFraction * m.total_mass * m.gravity);
  o.full_torque_envelope = g.full_torque_envelope;
  // Held for every landing: a late touchdown (lower ground) past α_fSS then meets the ground by
  // the robot turning as one body about the stance foot, where the extrapolated polynomials of
  // an impact landing go on spreading the legs, and the longer step's impact stalls the next
  // one (measured in MuJoCo on the 0.75 m/s impact gait, 0.035 rad downhill).
  o.hold_references_past_fss = true;
  return o;
}

Walker::Walker(Model model, GaitEvaluation<double> gait, const Parameterisation& par,
               WalkerOptions options)
    : model_(std::move(model)),
      gait_(std::move(gait)),
      double_support_(par.hasDoubleSupport()),
      options_(options),
      apex_(model_, gait_.motion) {
  if (!gait_.motion_computed) throw std::invalid_argument("the gait has no motion");
  const LeanLever lever = leanLever(model_, gait_.motion);
  slope_lean_ratio_ = slopeLeanRatio(lever);
  start_alpha_ = gait_.motion.q_iSS(0);
  lean_torque_ = model_.total_mass * model_.gravity * lever.shift;
}

WalkerState Walker::initialState() const {
  const GaitMotion<double>& mo = gait_.motion;
  const Vec5 q = mo.q_iSS;
  Vec5 qd;
  qd(0) = mo.alphadot_iSS;
  for (int j = 0; j < 4; ++j) qd(j + 1) = mo.ss_path[j](q(0)).first * mo.alphadot_iSS;
  const ChainState<double> st = chainState(model_, q, qd);
  WalkerState s;
  s.hip = chainPoint(model_.pinned.hip, st);
  s.hip_rate = chainPointVelocity(model_.pinned.hip, st);
  s.pitch = q(0) + q(1) - q(2);  // θ3 − π/2 (1.13)
  s.pitch_rate = qd(0) + qd(1) - qd(2);
  s.phi = jointSpeeds(q);  // φ = D_Γᵀ q, linear like ω
  s.phi_rate = jointSpeeds(qd);
  s.contact = {true, false};
  return s;
}

double Walker::phaseProgress(double alpha) const {
  const GaitMotion<double>& mo = gait_.motion;
  return (alpha - mo.q_iSS(0)) / (mo.alpha_fSS - mo.q_iSS(0));
}

// Touchdown: the swing foot's contact once the SS is past kTouchdownArmed; a double support
// follows (leg 1 becomes the front leg) or, after an impact into single support, the next step
// starts at once. Lift-off: α reaches the DS end α_fDS, or the rear foot leaves the ground.
void Walker::switchPhase(const WalkerState& s) {
  Vec5 q, qd;
  pinnedStateOf(s, leg1_, q, qd);
  const GaitMotion<double>& mo = gait_.motion;
  if (phase_ == WalkerPhase::SingleSupport) {
    if (!s.contact[side(other(leg1_))] || phaseProgress(q(0)) < kTouchdownArmed) return;
    slope_ = groundSlopeBetweenFeet(model_, q);
    options_.swing_end_offset = slopeSwingEnd();
    leg1_ = other(leg1_);
    pinnedStateOf(s, leg1_, q, qd);
    // The next single support starts at α_iSS, or where the new stance leg already is.
    start_alpha_ = phaseProgress(q(0)) > 0.0 ? q(0) : mo.q_iSS(0);
    ++steps_;
    phase_start_ = s.t;
    const double error = stepSpeedError(s);
    const double scale = rateScale(error);
    regulateLean(error, double_support_ ? scale : 1.0, s.t, apexRatio(q, qd) * apex_.gait());
    if (!double_support_) return;
    phase_ = WalkerPhase::DoubleSupport;
    rear_contact_ = s.t;
    recontacted_ = false;
    // Where the rear foot is on the ground, in the pinned frame of the front foot.
    rear_target_ = chainPoint(model_.pinned.foot2, chainState(model_, q, qd)) -
                   Vec2(0.0, kRecontactDepth);
    ds_ = dsReference(law(), s.t, q, qd, scale);
    return;
  }
  const double alpha_end = mo.ds_alpha(mo.T_DS).value;
  const double sigma = alpha_end < mo.ds_alpha(0.0).value ? -1.0 : 1.0;
  if (s.contact[side(other(leg1_))]) rear_contact_ = s.t;
  if (recontact_) {
    // The rear foot is back: the double support resumes, its durations counted from here.
    if (rear_contact_ == s.t) {
      recontact_ = false;
      phase_start_ = s.t;
    } else if (s.t - recontact_start_ >= kRecontactTime) {
      recontact_ = false;
      phase_ = WalkerPhase::SingleSupport;
      phase_start_ = lean_start_ = s.t;
    }
    return;
  }
  // Time-optimal control: the DS ends at α_fDS once α̇ is on the (scaled) lift-off rate, or
  // after T_DS past α_fDS: a late touchdown (downhill) lands beyond α_fDS, and ending the DS
  // there would skip the only phase that regulates the speed.
  const bool past_end = sigma * (q(0) - alpha_end) >= 0.0;
  const double target = ds_.rate_scale * mo.alphadot_iSS;
  const bool on_rate = std::abs(qd(0) - target) <= options_.lift_off_rate_tolerance * std::abs(target);
  // Nor does it end while the single support it starts would not pass its apex with
  // apex_energy_fraction of the gait's energy (the outputs lagging, a slow touchdown), unless it
  // has lasted kMaxDsExtension planned durations.
  const double elapsed = s.t - phase_start_;
  const auto energetic = [&] {
    return elapsed >= kMaxDsExtension * mo.T_DS ||
           apexRatio(q, qd) >= options_.apex_energy_fraction;
  };
  // After a re-contact the DS lasts at least T_DS: the outputs left the DS references while the
  // rear foot was driven back, and a lift-off on rate at once starts a single support off its path
  // that the apex prediction overrates (the 0.8 m/s gait 0.02 rad uphill lifted off 11 ms after
  // the re-contact with 0.64 of the gait's energy predicted and fell back).
  const bool rate_ends = on_rate && !recontacted_;
  const bool ended = options_.ds_control == DsAlphaControl::Cubic
                         ? s.t >= ds_.t_end
                         : past_end && (rate_ends || elapsed >= mo.T_DS) && energetic();
  const bool rear_lost = s.t - rear_contact_ >= options_.rear_lift_time;
  if (!ended && rear_lost && !recontacted_ && slope_ > options_.slope_deadband &&
      apexRatio(q, qd) < options_.apex_energy_fraction) {
    // The front foot's impact on rising ground lifted the rear foot and the single support
    // would not pass its apex: the foot is put back where it left the ground, the only support
    // that can give the step the energy of its climb. (Downhill, the ratio measured in the
    // hard landing's bounce is no guide, and the step has energy to spare.)
    recontact_ = recontacted_ = true;
    recontact_start_ = s.t;
    return;
  }
  if (ended || rear_lost) {
    phase_ = WalkerPhase::SingleSupport;
    phase_start_ = lean_start_ = s.t;
    measureLiftOffEnergy(q, qd);
  }
}

// The walk starts in single support (initialState): the stance leg is the one whose α is
// nearer the phase's start. The contact flags cannot tell on inclined ground: the swing foot,
// behind the stance foot, may touch the higher ground downhill while the stance foot, at rest,
// barely loads it.
Stance Walker::startingLeg(const WalkerState& s) const {
  const auto progress = [&](Stance leg) {
    Vec5 q, qd;
    pinnedStateOf(s, leg, q, qd);
    return std::abs(phaseProgress(q(0)));
  };
  return progress(Stance::Left) <= progress(Stance::Right) ? Stance::Left : Stance::Right;
}

Vec4 slopeSwingOffset(const Model& model, const GaitMotion<double>& mo, double slope,
                      double shortening) {
  const Vec5 zero = Vec5::Zero();
  const Vec2 end = chainPoint(model.pinned.foot2, chainState(model, mo.q_fSS, zero));
  const double length = (1.0 - shortening) * end(0);
  const Vec2 target(length, end(1) + length * std::tan(slope));
  Vec5 q = mo.q_fSS;
  // Newton on the swing leg's (δ3, δ4): the trunk, the stance leg and so α keep their path.
  for (int k = 0; k < 8; ++k) {
    const ChainState<double> st = chainState(model, q, zero);
    const Vec2 r = chainPoint(model.pinned.foot2, st) - target;
    if (r.norm() < 1e-12) break;
    q.tail<2>() -= chainPointJacobian(model, model.pinned.foot2, st).rightCols<2>().inverse() * r;
  }
  Vec4 offset = Vec4::Zero();
  offset.tail<2>() = q.tail<2>() - mo.q_fSS.tail<2>();
  return offset;
}

// The swing foot's end on the slope measured at the last touchdown, 0 on level ground. Uphill
// the foot meets the rising ground at the planned step length instead of early, with its
// planned forward speed (an impact that lifts the rear foot). Downhill it lands on the lower
// ground, kDownhillShortening of the step short of the planned length: the step descends less
// (m g L sin γ per step) and lands before the robot has turned past the double support's end.
Vec4 Walker::slopeSwingEnd() const {
  if (std::abs(slope_) <= options_.slope_deadband) return Vec4::Zero();
  return slopeSwingOffset(model_, gait_.motion, slope_, slope_ < 0.0 ? kDownhillShortening : 0.0);
}

double groundSlopeBetweenFeet(const Model& model, const Vec5& q) {
  const Vec2 d = chainPoint(model.pinned.foot2, chainState(model, q, Vec5(Vec5::Zero())));
  return std::atan2(d(1), d(0));
}

// The lean that compensates a downhill slope measured at the last touchdown (slopeLeanRatio), 0
// above −slope_deadband (the touchdown's measurement on level ground). Uphill the swing foot's
// end is raised instead (slopeSwingOffset): the robot keeps the gait's stance motion, and the
// double support's rate regulation gives each step the energy of its climb (a forward lean on
// top of it drove the default gait to +59 % on a 0.035 rad slope).
double Walker::slopeLean() const {
  if (slope_ >= -options_.slope_deadband) return 0.0;
  return -options_.slope_compensation * slope_lean_ratio_ * slope_;
}

double Walker::stanceFootX(const WalkerState& s) const {
  Vec5 q, qd;
  pinnedStateOf(s, leg1_, q, qd);
  return s.hip(0) - chainPoint(model_.pinned.hip, chainState(model_, q, qd))(0);
}

double Walker::stepSpeedError(const WalkerState& s) {
  const double x = stanceFootX(s);
  const double speed = (x - stance_x_) / (s.t - stance_t_);
  stance_x_ = x;
  stance_t_ = s.t;
  return speed / gait_.speed - 1.0;
}

// The rate scale 1 − speed_gain × Σ within ±max_rate_correction, and never below the start
// rate that passes the apex with apex_energy_fraction of the gait's energy (the sum is clamped
// there, so the lean's second stage sees the bound as a saturation). On a slope the bound
// counts with the energy the last lift-off delivered above the prediction (measureLiftOffEnergy).
double Walker::lowestRateScale() const {
  const double fraction = options_.apex_energy_fraction - liftoff_energy_excess_ / apex_.gait();
  return std::clamp(apex_.minStartRateScale(start_alpha_, fraction),
                    1.0 - options_.max_rate_correction, 1.0);
}

// At lift-off: σ_apex² predicted from the measured state minus the prediction from the gait's
// start at the double support's target rate (ApexEnergy::fromStart), when positive, on a slope;
// 0 on level ground. The start a DS delivers on a slope is off the gait's path (the rear foot
// lower or higher, the swing foot's end offset), and the path's prediction then undervalues it:
// measured on the 0.75 m/s C&A gait 0.035 rad uphill, 1.0 of the gait's energy at lift-off for
// 0.13 predicted at rate scale 0.85, and the bound held the walk at +15 % speed. The excess is
// the start's offset in Φ (σ² − Φ(α) is conserved), so it adds to the energy at any rate: a
// ratio would grow without bound where the path's prediction nears 0 (the bound's own rate).
void Walker::measureLiftOffEnergy(const Vec5& q, const Vec5& qd) {
  const double predicted = apex_.fromStart(start_alpha_, ds_.rate_scale, 0.0);
  const bool sloped = std::abs(slope_) > options_.slope_deadband;
  liftoff_energy_excess_ =
      sloped ? std::max(0.0, apexRatio(q, qd) * apex_.gait() - predicted) : 0.0;
}

double Walker::rateScale(double error) {
  const double m = options_.max_rate_correction;
  speed_error_sum_ = std::clamp(speed_error_sum_ + error, -m / options_.speed_gain,
                                (1.0 - lowestRateScale()) / options_.speed_gain);
  return 1.0 - options_.speed_gain * speed_error_sum_;
}

// The largest backward lean of the regulation with which the next single support still passes
// its apex with apex_energy_fraction of the gait's energy, started at the DS's target rate
// (rate_scale times the gait's) or with the energy of the touchdown state when that is larger
// (a late touchdown downhill, which the double support cannot brake): a lean back moves the
// centre of mass behind its path by ∂x_c/∂pitch per radian all the way to the apex
// (ApexEnergy::fromStart, linear in the lean).
double Walker::maxBackLean(double rate_scale, double touchdown_energy) const {
  const double upright = apex_.fromStart(start_alpha_, rate_scale, 0.0);
  const double spare =
      std::max(upright, touchdown_energy) - options_.apex_energy_fraction * apex_.gait();
  const double cost = upright - apex_.fromStart(start_alpha_, rate_scale, lean_torque_);
  return cost > 0.0 ? std::max(0.0, spare / cost) : options_.max_lean;
}

// Single-support speed regulation: the trunk leans back (forward) after a step faster (slower)
// than the gait's, PI on the step speed error: the centre of mass behind (ahead of) its planned
// path over the stance foot decelerates (accelerates) the zero dynamics. Leg-1 δ2 is the
// stance hip: pitch = α + δ1 − δ2 (1.13) with the inter-femur angle δ3 kept, so the swing leg's
// absolute path is the planned one. With a double support the lean is the second stage: it
// acts once the double support's rate correction is at its bound (a slope, a large push) and
// until its own integral has returned to 0; a gait without one has only this regulation. The
// slope compensation (slopeLean) is added as a feedforward: the integral then removes what the
// model leaves.
void Walker::regulateLean(double error, double scale, double t, double touchdown_energy) {
  const double m = options_.max_lean;
  const double bound =
      speed_error_sum_ > 0.0 ? 1.0 - lowestRateScale() : options_.max_rate_correction;
  const bool rate_saturated =
      std::abs(speed_error_sum_) * options_.speed_gain >= bound * (1.0 - 1e-9);
  const bool active = !double_support_ || rate_saturated || lean_integral_ != 0.0;
  double lean = 0.0;
  if (active) {
    const double before = lean_integral_;
    lean_integral_ = std::clamp(lean_integral_ + options_.lean_integral_gain * error, -m, m);
    // The second stage stops where it started: the rate correction takes over again.
    if (double_support_ && !rate_saturated && before * lean_integral_ <= 0.0) lean_integral_ = 0.0;
    const double back = std::min(m, maxBackLean(scale, touchdown_energy));
    lean_integral_ = std::min(lean_integral_, back);
    lean = std::clamp(options_.lean_gain * error + lean_integral_, -m, back);
  }
  lean = std::clamp(lean + slopeLean(), -m, m);
  lean_from_ = leanAt(t).value;
  lean_to_ = lean;
  // The double support keeps the previous lean; the new one blends in from its end.
  lean_start_ = double_support_ ? std::numeric_limits<double>::infinity() : t;
}

// The lean blended from lean_from_ to lean_to_ by a C¹ smoothstep over kLeanBlend T_SS from the
// single support's start, in time: a step that stalls gets its lean all the same.
PolyValue<double> Walker::leanAt(double t) const {
  const double h = lean_to_ - lean_from_;
  const PolyValue<double> w = smoothstep(t, lean_start_, kLeanBlend * gait_.motion.T_SS);
  if (w.value >= 1.0 || h == 0.0) return {lean_to_, 0.0, 0.0};
  return {lean_from_ + h * w.value, h * w.first, h * w.second};
}

// The apex energy predicted from (q, q̇), leg 1 the stance (in DS the front) leg, over the
// gait's.
double Walker::apexRatio(const Vec5& q, const Vec5& qd) const {
  const StanceMomentum m = stanceMomentum(model_, q, qd);
  return apex_.predicted(q(0), m.sigma, m.gravity_torque) / apex_.gait();
}

// The references' offset at t: the regulation's lean on leg-1 δ2 (back: δ2 down, pitch =
// α + δ1 − δ2), with its time derivatives.
TimedOffset Walker::referenceOffset(double t) const {
  const PolyValue<double> lean = leanAt(t);
  TimedOffset o;
  o.value(1) = -lean.value;
  o.rate(1) = -lean.first;
  o.acceleration(1) = -lean.second;
  return o;
}

bool Walker::fallen(const WalkerState& s, const Vec5& q) const {
  if (std::abs(s.pitch) > options_.fall_pitch) return true;
  if (s.t - last_contact_ > options_.flight_time) return true;
  const GaitMotion<double>& mo = gait_.motion;
  const double planned = phase_ == WalkerPhase::SingleSupport ? mo.T_SS : mo.T_DS;
  const double elapsed = s.t - phase_start_;
  if (elapsed > options_.stall_factor * planned + 0.05) return true;
  // α running backwards past the phase's start: the robot falls back.
  return phase_ == WalkerPhase::SingleSupport && phaseProgress(q(0)) < -0.5;
}

WalkerCommand Walker::torques(const WalkerState& s) {
  WalkerCommand c;
  if (!started_) {
    started_ = true;
    leg1_ = startingLeg(s);
    phase_start_ = last_contact_ = stance_t_ = s.t;
    stance_x_ = stanceFootX(s);
  }
  if (s.contact[0] || s.contact[1]) last_contact_ = s.t;
  if (phase_ != WalkerPhase::Fallen) switchPhase(s);
  Vec5 q, qd;
  pinnedStateOf(s, leg1_, q, qd);
  if (phase_ == WalkerPhase::Fallen || fallen(s, q)) {
    phase_ = WalkerPhase::Fallen;
    c.fallen = true;
    return c;
  }
  options_.timed_offset = referenceOffset(s.t);
  c.law = phase_ == WalkerPhase::SingleSupport ? singleSupportControl(law(), q, qd)
          : recontact_ ? recontactControl(law(), rear_target_, q, qd)
                       : doubleSupportControl(law(), ds_, s.t, q, qd);
  // The envelope at the current joint speeds holds whatever the projection could do.
  const Vec4 limit = jointTorqueLimits(model_.robot.envelope, jointSpeeds(qd),
                                       options_.full_torque_envelope);
  c.tau = physicalOrder(c.law.gamma_star.cwiseMax(-limit).cwiseMin(limit), leg1_);
  return c;
}

}  // namespace gaitopt
