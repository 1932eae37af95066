// The reference walker on measured states: the measured-state → pinned-coordinate map, its
// initial state, the law's torques at that state, the phase switching on contact events, the
// torque envelope, the fall judgement.
#include <catch2/catch.hpp>

#include <cmath>

#include "gaitopt/control/walker.hpp"
#include "gaitopt/gait/constraints/torque_envelope.hpp"
#include "gaitopt/model/chain_kinematics.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/joint_friction.hpp"
#include "test_default_gait.hpp"
#include "walker_states.hpp"

namespace gaitopt::test {
namespace {

Walker walkerOf(const ShippedGait& g) {
  return Walker(g.model, g.evaluation, g.gait.options.parameterisation,
                walkerOptionsFor(g.gait.options, g.model));
}

}  // namespace

TEST_CASE("Walker state map recovers the pinned coordinates for either stance leg",
          "[control][walker]") {
  const DefaultGait g;
  Vec5 q, qd;
  ssState(g.evaluation.motion, 0.5 * (g.evaluation.motion.q_iSS(0) + g.evaluation.motion.alpha_fSS),
          -0.8, q, qd);
  for (Stance leg : {Stance::Left, Stance::Right}) {
    Vec5 q2, qd2;
    pinnedStateOf(measured(g.model, q, qd, leg, 0.3, {true, false}, 0.0), leg, q2, qd2);
    CHECK((q2 - q).cwiseAbs().maxCoeff() < 1e-14);
    CHECK((qd2 - qd).cwiseAbs().maxCoeff() < 1e-14);
  }
  const Vec4 v(1.0, 2.0, 3.0, 4.0);
  CHECK(physicalOrder(v, Stance::Left) == v);
  CHECK(physicalOrder(physicalOrder(v, Stance::Right), Stance::Right) == v);
  CHECK(physicalOrder(v, Stance::Right)(0) == 4.0);
}

TEST_CASE("Walker initial state is the gait's SS start on the left foot at rest at x = 0",
          "[control][walker]") {
  const DefaultGait g;
  Walker w = walkerOf(g);
  const WalkerState s = w.initialState();
  const GaitMotion<double>& mo = g.evaluation.motion;
  Vec5 q, qd;
  pinnedStateOf(s, Stance::Left, q, qd);
  CHECK((q - mo.q_iSS).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(qd(0) == Approx(mo.alphadot_iSS).epsilon(1e-12));
  CHECK(s.t == 0.0);
  CHECK(s.contact[0]);
  CHECK_FALSE(s.contact[1]);
  // The hip seen from foot 1 at the origin; foot 1's velocity is zero (rest).
  const ChainState<double> st = chainState(g.model, q, qd);
  CHECK((s.hip - chainPoint(g.model.pinned.hip, st)).norm() < 1e-14);
  CHECK((s.hip_rate - chainPointVelocity(g.model.pinned.hip, st)).norm() < 1e-14);
  // On the virtual constraints: the law's outputs and their rates vanish, so the torques are
  // the feedforward alone, within the envelope.
  const WalkerCommand c = w.torques(s);
  CHECK_FALSE(c.fallen);
  CHECK(c.law.error.cwiseAbs().maxCoeff() < 1e-12);
  const Vec4 limit = jointTorqueLimits(g.model.robot.envelope, jointSpeeds(qd), true);
  CHECK((c.tau.cwiseAbs() - limit).maxCoeff() <= 1e-9);
  CHECK(w.phase() == WalkerPhase::SingleSupport);
}

TEST_CASE("Walker switches phase on the swing foot's contact, not on time or the phase",
          "[control][walker]") {
  const DefaultGait g;
  Walker w = walkerOf(g);
  const GaitMotion<double>& mo = g.evaluation.motion;
  Vec5 q, qd;
  // Early in the SS a contact of the swing foot (it just lifted off) is not a touchdown.
  ssState(mo, mo.q_iSS(0) + 0.2 * (mo.alpha_fSS - mo.q_iSS(0)), mo.alphadot_iSS, q, qd);
  w.torques(measured(g.model, q, qd, Stance::Left, 0.0, {true, true}, 0.1));
  CHECK(w.phase() == WalkerPhase::SingleSupport);
  CHECK(w.steps() == 0);
  // Past the SS end without contact: still SS (the references go on past α_fSS).
  ssState(mo, mo.alpha_fSS + 0.01 * (mo.alpha_fSS - mo.q_iSS(0)), mo.alphadot_fSS, q, qd);
  w.torques(measured(g.model, q, qd, Stance::Left, 0.0, {true, false}, 0.5));
  CHECK(w.phase() == WalkerPhase::SingleSupport);
  // The swing foot's contact: touchdown, a DS on the right foot as leg 1.
  ssState(mo, mo.alpha_fSS, mo.alphadot_fSS, q, qd);
  w.torques(measured(g.model, q, qd, Stance::Left, 0.0, {true, true}, 0.55));
  CHECK(w.phase() == WalkerPhase::DoubleSupport);
  CHECK(w.leg1() == Stance::Right);
  CHECK(w.steps() == 1);
  // Just past α_fDS, T_DS later, the SS on the right leg starts.
  ssState(mo, mo.q_iSS(0) + 0.01 * (mo.alpha_fSS - mo.q_iSS(0)), mo.alphadot_iSS, q, qd);
  w.torques(measured(g.model, q, qd, Stance::Right, 0.3, {true, true}, 0.55 + 2.0 * mo.T_DS));
  CHECK(w.phase() == WalkerPhase::SingleSupport);
  CHECK(w.leg1() == Stance::Right);
}

TEST_CASE("Walker judges a tipped trunk or a flight as fallen and stays fallen",
          "[control][walker]") {
  const DefaultGait g;
  {
    Walker w = walkerOf(g);
    WalkerState s = w.initialState();
    s.pitch = 1.2;
    const WalkerCommand c = w.torques(s);
    CHECK(c.fallen);
    CHECK(c.tau == Vec4::Zero());
    CHECK(w.torques(w.initialState()).fallen);
  }
  {
    Walker w = walkerOf(g);
    WalkerState s = w.initialState();
    CHECK_FALSE(w.torques(s).fallen);
    s.contact = {false, false};
    s.t = 0.05;
    CHECK_FALSE(w.torques(s).fallen);  // a short flight (contact chatter) is not a fall
    s.t = 0.2;
    CHECK(w.torques(s).fallen);
  }
}

TEST_CASE("Walker torques stay within the envelope at the joints' speeds", "[control][walker]") {
  const DefaultGait g;
  Walker w = walkerOf(g);
  const GaitMotion<double>& mo = g.evaluation.motion;
  Vec5 q, qd;
  for (int k = 0; k < 20; ++k) {
    ssState(mo, mo.q_iSS(0) + 0.04 * k * (mo.alpha_fSS - mo.q_iSS(0)), -1.0, q, qd);
    // Far from the constraints: large outputs, large demanded torques.
    q(1) += 0.2 * std::sin(k);
    qd(3) += 3.0 * std::cos(k);
    const WalkerCommand c = w.torques(measured(g.model, q, qd, Stance::Left, 0.0, {true, false}, 0.01 * k));
    const Vec4 limit = jointTorqueLimits(g.model.robot.envelope, jointSpeeds(qd), true);
    CHECK((c.tau.cwiseAbs() - limit).maxCoeff() <= 1e-9);
  }
}

TEST_CASE("Walker starts on the leg whose alpha is at the SS start, whatever the contact flags",
          "[control][walker]") {
  // Downhill the swing foot behind touches the higher ground while the stance foot at rest
  // barely loads its own: the first sample may say (0, 1).
  const DefaultGait g;
  Walker w = walkerOf(g);
  WalkerState s = w.initialState();
  s.contact = {false, true};
  w.torques(s);
  CHECK(w.leg1() == Stance::Left);
  s.t = 0.001;
  s.contact = {true, true};
  w.torques(s);
  CHECK(w.steps() == 0);
  CHECK(w.phase() == WalkerPhase::SingleSupport);
}

namespace {

// One step of the left leg from x = 0 ending at t_touchdown with the right foot's touchdown at
// x_right: the step's end turned by `turn` about the stance foot (inclined ground), at
// speed_ratio times the gait's speed.
struct Touchdown {
  double x_right, t;
};
Touchdown touchdownAfterOneStep(Walker& w, const ShippedGait& g, double speed_ratio, double turn) {
  const GaitMotion<double>& mo = g.evaluation.motion;
  w.torques(w.initialState());
  Vec5 q, qd;
  ssState(mo, mo.alpha_fSS, mo.alphadot_fSS, q, qd);
  q(0) += turn;
  // The right foot's x from the left foot at 0: the hip seen from both feet.
  const WalkerState left = measured(g.model, q, qd, Stance::Left, 0.0, {true, true}, 0.0);
  Vec5 qr, qdr;
  pinnedStateOf(left, Stance::Right, qr, qdr);
  const double x_right =
      left.hip(0) - chainPoint(g.model.pinned.hip, chainState(g.model, qr, qdr))(0);
  const double t_touchdown = x_right / (speed_ratio * g.evaluation.speed);
  w.torques(measured(g.model, q, qd, Stance::Left, 0.0, {true, true}, t_touchdown));
  REQUIRE(w.steps() == 1);
  return {x_right, t_touchdown};
}

// The leg-1 δ2 output of the walker's SS law (the stance hip) with the state on the gait's
// constraints on the right leg, after one step of the left leg: at the single support's start
// (the rear foot lifted 30 ms after the touchdown when the gait has a double support), half the
// lean's blend later with the robot stalled at that start, and after the blend at s = 0.2.
struct LeanRun {
  double error_at_start, error_mid_blend, error_after_blend;
};
LeanRun leanAfterOneStep(const ShippedGait& g, WalkerOptions o, double speed_ratio,
                         double turn = 0.0) {
  Walker w(g.model, g.evaluation, g.gait.options.parameterisation, o);
  const GaitMotion<double>& mo = g.evaluation.motion;
  const Touchdown td = touchdownAfterOneStep(w, g, speed_ratio, turn);
  const auto error_at = [&](double progress, double t) {
    Vec5 q, qd;
    ssState(mo, mo.q_iSS(0) + progress * (mo.alpha_fSS - mo.q_iSS(0)), mo.alphadot_iSS, q, qd);
    // The rear (left) foot off the ground: the DS, if any, ends.
    return w.torques(measured(g.model, q, qd, Stance::Right, td.x_right, {false, true}, t))
        .law.error(1);
  };
  const double t_ss = td.t + (g.gait.options.parameterisation.hasDoubleSupport() ? 0.03 : 0.0);
  const double blend = kLeanBlend * mo.T_SS;
  LeanRun r;
  r.error_at_start = error_at(0.0, t_ss);
  REQUIRE(w.phase() == WalkerPhase::SingleSupport);
  r.error_mid_blend = error_at(0.0, t_ss + 0.5 * blend);
  r.error_after_blend = error_at(0.2, t_ss + 2.0 * blend);
  REQUIRE(w.phase() == WalkerPhase::SingleSupport);
  return r;
}

// The walker's options with the lean's PI gains 0.1 and 0.05 rad per relative speed error.
WalkerOptions leanOptions(const ShippedGait& g, double apex_energy_fraction) {
  WalkerOptions o = walkerOptionsFor(g.gait.options, g.model);
  o.lean_gain = 0.1;
  o.lean_integral_gain = 0.05;
  o.apex_energy_fraction = apex_energy_fraction;
  return o;
}

}  // namespace

TEST_CASE("Walker leans the trunk back after a fast step, blended in time from the SS start",
          "[control][walker]") {
  const ShippedGait g("configs/gait/default_impact.yaml");
  WalkerOptions o = leanOptions(g, 0.0);  // the lean's energy bound is checked below
  // A step at twice the gait's speed: relative error +1, lean 0.1 + 0.05 rad. The output
  // δ2 − (δ_d2 − lean) of a state on the planned constraints is the lean (pitch = α + δ1 − δ2).
  const LeanRun fast = leanAfterOneStep(g, o, 2.0);
  CHECK(fast.error_at_start == Approx(0.0).margin(1e-12));
  // Half the blend's time later, the robot stalled at the start: half the lean
  // (smoothstep(1/2) = 1/2), whatever the phase variable does.
  CHECK(fast.error_mid_blend == Approx(0.5 * 0.15).margin(1e-12));
  CHECK(fast.error_after_blend == Approx(0.15).margin(1e-12));
  // Slower: leans forward; bounded by max_lean.
  o.max_lean = 0.02;
  CHECK(leanAfterOneStep(g, o, 0.5).error_after_blend == Approx(-0.02).margin(1e-12));
  // No lean at the gait's speed.
  CHECK(leanAfterOneStep(g, o, 1.0).error_after_blend == Approx(0.0).margin(1e-9));
}

TEST_CASE("Walker bounds the lean back by the energy the next single support needs at its apex",
          "[control][walker]") {
  // This impact gait passes its apex with a tenth of its start energy: a lean back of 0.15 rad
  // would take more than half of it.
  const ShippedGait g("tests/data/gait_optima/default_impact_low_apex.yaml");
  double previous = 0.15;
  for (double fraction : {0.5, 0.8}) {
    const double lean = leanAfterOneStep(g, leanOptions(g, fraction), 2.0).error_after_blend;
    CHECK(lean > 0.0);
    CHECK(lean < previous - 0.01);
    previous = lean;
  }
  // A slow step's lean forward is not bounded: 0.1 × 0.5 + 0.05 × 0.5.
  CHECK(leanAfterOneStep(g, leanOptions(g, 0.8), 0.5).error_after_blend ==
        Approx(-0.075).margin(1e-12));
}

TEST_CASE("Walker with a double support leans only once the DS rate correction is at its bound",
          "[control][walker]") {
  const DefaultGait g;
  WalkerOptions o = leanOptions(g, 0.0);
  o.max_rate_correction = 0.15;
  // +50 % within the rate correction's reach (0.2 × 0.5 < 0.15): the DS alone regulates.
  CHECK(leanAfterOneStep(g, o, 1.5).error_after_blend == Approx(0.0).margin(1e-12));
  // Beyond it (0.2 × 2 > 0.15): the lean acts, 0.1 × 2 + 0.05 × 2.
  CHECK(leanAfterOneStep(g, o, 3.0).error_after_blend == Approx(0.3).margin(1e-9));
  // The DS's braking ends where its start rate would leave less than half the gait's apex
  // energy (about 9 % below the gait's rate on this gait): +50 % is then beyond it.
  o.apex_energy_fraction = 0.5;
  CHECK(leanAfterOneStep(g, o, 1.5).error_after_blend > 0.0);
}

TEST_CASE("Walker holds the double support while the single support would not pass its apex",
          "[control][walker]") {
  // The 0.3 m/s gait passes its apex with about a fifth of its start energy: 10 % under its
  // start rate it would not pass it (control/apex_energy.hpp).
  const ShippedGait g("configs/gait/optimal_0.3.yaml");
  const GaitMotion<double>& mo = g.evaluation.motion;
  WalkerOptions o = walkerOptionsFor(g.gait.options, g.model);
  o.lift_off_rate_tolerance = 0.2;  // 10 % off the target rate counts as on it
  const auto phase_after = [&](double rate_scale, double t_after, double fraction) {
    o.apex_energy_fraction = fraction;
    Walker w(g.model, g.evaluation, g.gait.options.parameterisation, o);
    const Touchdown td = touchdownAfterOneStep(w, g, 1.0, 0.0);
    REQUIRE(w.phase() == WalkerPhase::DoubleSupport);
    Vec5 q, qd;  // past the DS end α_fDS = α_iSS, on the SS path, both feet down
    ssState(mo, mo.q_iSS(0) + 0.01 * (mo.alpha_fSS - mo.q_iSS(0)), rate_scale * mo.alphadot_iSS, q,
            qd);
    w.torques(measured(g.model, q, qd, Stance::Right, td.x_right, {true, true}, td.t + t_after));
    return w.phase();
  };
  // On the rate, T_DS after the touchdown: the DS ends.
  CHECK(phase_after(1.0, mo.T_DS, 0.5) == WalkerPhase::SingleSupport);
  // 10 % slow: on the (widened) rate, but the SS would fall back: held.
  CHECK(phase_after(0.9, mo.T_DS, 0.5) == WalkerPhase::DoubleSupport);
  // ... unless the energy check is off, or the DS has lasted its longest.
  CHECK(phase_after(0.9, mo.T_DS, 0.0) == WalkerPhase::SingleSupport);
  CHECK(phase_after(0.9, 1.01 * kMaxDsExtension * mo.T_DS, 0.5) == WalkerPhase::SingleSupport);
}

TEST_CASE("Walker measures the slope between the feet and leans back downhill by its CoM shift",
          "[control][walker]") {
  const DefaultGait g;
  const GaitMotion<double>& mo = g.evaluation.motion;
  WalkerOptions o = walkerOptionsFor(g.gait.options, g.model);
  Vec5 q_end, qd;
  ssState(mo, mo.alpha_fSS, mo.alphadot_fSS, q_end, qd);
  // The touchdown configuration turned by δ about foot 1 turns the feet's direction by ±δ.
  const auto slope = [&](double turn) {
    return groundSlopeBetweenFeet(g.model, Vec5(q_end + turn * Vec5::Unit(0)));
  };
  CHECK(std::abs(slope(0.0)) < 2e-3);  // the gait lands on level ground
  const double per_turn = (slope(1e-3) - slope(-1e-3)) / 2e-3;
  CHECK(std::abs(per_turn) == Approx(1.0).epsilon(1e-6));
  const double gamma = -0.03;
  const double turn = (gamma - slope(0.0)) / per_turn;
  CHECK(slope(turn) == Approx(gamma).margin(1e-9));
  // At the gait's speed only the slope compensation leans the trunk.
  const double lean = leanAfterOneStep(g, o, 1.0, turn).error_after_blend;
  CHECK(lean > 0.1);  // back, downhill
  // Independent of the walker's formula: the lean moves the centre of mass at mid single
  // support back by as much as turning the configuration by the slope moves it forward.
  Vec5 q_mid;
  ssState(mo, 0.5 * (mo.q_iSS(0) + mo.alpha_fSS), mo.alphadot_iSS, q_mid, qd);
  const auto com_x = [&](const Vec5& q) { return pinnedTerms(g.model, q, Vec5(Vec5::Zero())).com(0); };
  const double forward = com_x(Vec5(q_mid + (gamma / per_turn) * Vec5::Unit(0))) - com_x(q_mid);
  const double back = com_x(Vec5(q_mid - lean * Vec5::Unit(2))) - com_x(q_mid);
  CHECK(std::abs(forward) > 0.01);
  CHECK(back == Approx(-forward).epsilon(0.1));
  // Within the dead band: level ground, no lean.
  const double small = (0.5 * o.slope_deadband - slope(0.0)) / per_turn;
  CHECK(leanAfterOneStep(g, o, 1.0, small).error_after_blend == Approx(0.0).margin(1e-9));
  o.slope_compensation = 0.0;
  CHECK(leanAfterOneStep(g, o, 1.0, turn).error_after_blend == Approx(0.0).margin(1e-9));
}

}  // namespace gaitopt::test

namespace gaitopt::test {

TEST_CASE("Walking controller gains: gain_scale scales the PD part of the torques linearly",
          "[control][walker]") {
  ControllerOptions o;
  o.gain_scale = 2.0;
  CHECK(pdGains(o).kp == Approx(2.0 * 40.0 * 40.0));
  CHECK(pdGains(o).kd == Approx(2.0 * 2.0 * 40.0));
  // Without the projection Γ* is affine in v = −Kp y − Kd ẏ: Γ(g) = Γ(0) + g (Γ(1) − Γ(0)).
  const DefaultGait g;
  const GaitMotion<double>& mo = g.evaluation.motion;
  Vec5 q = mo.q_iSS, qd = Vec5::Zero();
  qd(0) = mo.alphadot_iSS;
  q(2) += 0.05;
  qd(4) -= 0.4;
  const auto torques = [&](double scale) {
    ControllerOptions c;
    c.torque_limits = false;
    c.gain_scale = scale;
    return singleSupportControl({mo, g.model, c}, q, qd).gamma_star;
  };
  const Vec4 t0 = torques(0.0), t1 = torques(1.0), t3 = torques(3.0);
  CHECK((t1 - t0).norm() > 1.0);  // the outputs are off: the PD part is not negligible
  CHECK((t3 - (t0 + 3.0 * (t1 - t0))).cwiseAbs().maxCoeff() < 1e-9);
}

}  // namespace gaitopt::test
