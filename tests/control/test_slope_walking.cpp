// The walker on inclined ground: the swing foot's end moved onto the slope (slopeSwingOffset,
// ControllerOptions::swing_end_offset), the rear foot put back on the ground after a touchdown on
// rising ground lifted it (recontactControl, Walker::switchPhase).
#include <catch2/catch.hpp>

#include <cmath>

#include "gaitopt/control/walker.hpp"
#include "gaitopt/model/chain_kinematics.hpp"
#include "gaitopt/model/forward_dynamics.hpp"
#include "test_default_gait.hpp"
#include "walker_states.hpp"

namespace gaitopt::test {
namespace {

Vec2 foot2(const Model& m, const Vec5& q) {
  return chainPoint(m.pinned.foot2, chainState(m, q, Vec5(Vec5::Zero())));
}

}  // namespace

TEST_CASE("Swing offset puts the swing foot's end on the inclined ground at the step length",
          "[control][walker][slope]") {
  const DefaultGait g;
  const GaitMotion<double>& mo = g.evaluation.motion;
  const Vec2 end = foot2(g.model, mo.q_fSS);
  CHECK(end(0) > 0.2);  // the step length ahead of the stance foot
  for (double gamma : {0.035, 0.01, -0.02}) {
    const Vec4 o = slopeSwingOffset(g.model, mo, gamma);
    CHECK(o.head<2>().isZero());  // the stance leg and the trunk keep their path
    Vec5 q = mo.q_fSS;
    q.tail<2>() += o.tail<2>();
    const Vec2 shifted = foot2(g.model, q);
    CHECK(shifted(0) == Approx(end(0)).margin(1e-9));
    CHECK(shifted(1) - end(1) == Approx(end(0) * std::tan(gamma)).margin(1e-9));
  }
  CHECK(slopeSwingOffset(g.model, mo, 0.0).isZero(1e-12));
  // Shortened: on the same inclined line through the stance foot, nearer to it.
  const double gamma = -0.035, shortening = 0.17;
  Vec5 q = mo.q_fSS;
  q.tail<2>() += slopeSwingOffset(g.model, mo, gamma, shortening).tail<2>();
  const Vec2 shortened = foot2(g.model, q);
  CHECK(shortened(0) == Approx((1.0 - shortening) * end(0)).margin(1e-9));
  CHECK(shortened(1) - end(1) == Approx(shortened(0) * std::tan(gamma)).margin(1e-9));
}

TEST_CASE("Swing offset enters the SS references by the smoothstep of the phase",
          "[control][walker][slope]") {
  const DefaultGait g;
  const GaitMotion<double>& mo = g.evaluation.motion;
  ControllerOptions o = walkerOptionsFor(g.gait.options, g.model);
  o.torque_limits = false;
  const Vec4 offset(0.0, 0.0, 0.03, -0.05);
  // The outputs' shift by the offset at the phase s, the state on the gait's path.
  const auto shift = [&](double s) {
    Vec5 q, qd;
    ssState(mo, mo.q_iSS(0) + s * (mo.alpha_fSS - mo.q_iSS(0)), mo.alphadot_iSS, q, qd);
    o.swing_end_offset.setZero();
    const Vec4 planned = singleSupportControl({mo, g.model, o}, q, qd).error;
    o.swing_end_offset = offset;
    return Vec4(planned - singleSupportControl({mo, g.model, o}, q, qd).error);
  };
  CHECK(shift(0.0).isZero(1e-12));
  CHECK((shift(0.5) - 0.5 * offset).isZero(1e-12));
  CHECK((shift(0.25) - (0.25 * 0.25 * (3.0 - 0.5)) * offset).isZero(1e-12));
  CHECK((shift(1.0) - offset).isZero(1e-12));
  CHECK((shift(1.05) - offset).isZero(1e-12));  // held past α_fSS
}

TEST_CASE("Re-contact law brings a lifted rear foot down to its target on the pinned model",
          "[control][walker][slope]") {
  const DefaultGait g;
  const GaitMotion<double>& mo = g.evaluation.motion;
  const WalkerOptions o = walkerOptionsFor(g.gait.options, g.model);
  const WalkingController law{mo, g.model, o};
  // The DS start (both feet on the ground), the rear foot 5 mm up and moving up at 0.1 m/s.
  const Vec5 q_ground = mo.q_iDS;
  const Vec2 target = foot2(g.model, q_ground) - Vec2(0.0, kRecontactDepth);
  PinnedState x{q_ground, Vec5::Zero()};
  const ChainState<double> st = chainState(g.model, x.q, x.qd);
  const Eigen::Matrix2d J = chainPointJacobian(g.model, g.model.pinned.foot2, st).rightCols<2>();
  x.q.tail<2>() += J.inverse() * Vec2(0.0, 0.005);
  x.qd.tail<2>() = J.inverse() * Vec2(0.0, 0.1);
  const auto torque = [&](double, const PinnedState& s) {
    return recontactControl(law, target, s.q, s.qd).gamma_star;
  };
  const double start = (foot2(g.model, x.q) - target).norm();
  CHECK(start > 0.007);
  const PinnedState end = simulateSS(g.model, x, torque, 0.15, 2e-4, SignMode::Smooth);
  CHECK((foot2(g.model, end.q) - target).norm() < 0.05 * start);
  // The front leg on its DS references meanwhile.
  const ControlOutput e = recontactControl(law, target, end.q, end.qd);
  CHECK(std::abs(e.error(0)) < 0.01);
  CHECK(std::abs(e.error(1)) < 0.01);
}

TEST_CASE("Walker puts back a rear foot a touchdown on rising ground lifted, not on level ground",
          "[control][walker][slope]") {
  const DefaultGait g;
  const GaitMotion<double>& mo = g.evaluation.motion;
  const WalkerOptions o = walkerOptionsFor(g.gait.options, g.model);
  // The step's end with the swing foot on ground inclined by gamma (+ uphill), and 30 ms later
  // the same configuration on the right (front) leg with the rear (left) foot off the ground
  // and α̇ a third of the gait's start rate: the single support would stall before its apex.
  struct Touchdown {
    WalkerState touchdown, lifted;
    Vec5 q;  // pinned on the front leg
  };
  const auto touchdown = [&](double gamma) {
    Vec5 q, qd;
    ssState(mo, mo.alpha_fSS, mo.alphadot_fSS, q, qd);
    q.tail<2>() += slopeSwingOffset(g.model, mo, gamma).tail<2>();
    Touchdown td;
    td.touchdown = measured(g.model, q, qd, Stance::Left, 0.0, {true, true}, 0.6);
    Vec5 qd_front;
    pinnedStateOf(td.touchdown, Stance::Right, td.q, qd_front);
    const Vec5 slow = (mo.alphadot_iSS / 3.0) * Vec5::Unit(0);
    td.lifted = measured(g.model, td.q, slow, Stance::Right, 0.3, {false, true}, 0.63);
    return td;
  };
  // The phase and law 30 ms after the touchdown, and the phase `after` later with the rear foot
  // back on the ground or not.
  struct Run {
    WalkerPhase phase, after;
    Vec4 gamma;
  };
  const auto run = [&](double gamma, double after, bool back) {
    const Touchdown td = touchdown(gamma);
    Walker w(g.model, g.evaluation, g.gait.options.parameterisation, o);
    w.torques(w.initialState());
    w.torques(td.touchdown);
    REQUIRE(w.phase() == WalkerPhase::DoubleSupport);
    Run r;
    r.gamma = w.torques(td.lifted).law.gamma_star;
    r.phase = w.phase();
    WalkerState later = td.lifted;
    later.t += after;
    later.contact = {back, true};
    w.torques(later);
    r.after = w.phase();
    return r;
  };
  const Run up = run(0.035, 0.05, true);
  CHECK(up.phase == WalkerPhase::DoubleSupport);
  // Its law is the re-contact's, the target where the rear foot was at the touchdown.
  const Touchdown td = touchdown(0.035);
  const Vec2 target = foot2(g.model, td.q) - Vec2(0.0, kRecontactDepth);
  Vec5 q, qd;
  pinnedStateOf(td.lifted, Stance::Right, q, qd);
  const Vec4 expected = recontactControl({mo, g.model, o}, target, q, qd).gamma_star;
  CHECK((up.gamma - expected).norm() <= 1e-9 * expected.norm());
  // The foot back on the ground: the double support goes on.
  CHECK(up.after == WalkerPhase::DoubleSupport);
  // Not back within the re-contact's time: the single support starts.
  CHECK(run(0.035, 1.01 * kRecontactTime, false).after == WalkerPhase::SingleSupport);
  // Level ground: the double support ends on the lost rear foot.
  CHECK(run(0.0, 0.05, true).phase == WalkerPhase::SingleSupport);

  // Past α_fDS on the lift-off rate, `after` past the touchdown (level) or past the rear foot's
  // return (uphill): the DS ends on the rate at once without a re-contact, but lasts T_DS after
  // one (its outputs left the DS references while the rear foot was driven back).
  const auto phase_on_rate = [&](double gamma, double after) {
    WalkerOptions wide = o;
    wide.lift_off_rate_tolerance = 0.5;
    const Touchdown td = touchdown(gamma);
    Walker w(g.model, g.evaluation, g.gait.options.parameterisation, wide);
    w.torques(w.initialState());
    w.torques(td.touchdown);
    double t = td.touchdown.t;
    if (gamma > 0.0) {
      w.torques(td.lifted);
      WalkerState back = td.lifted;
      back.t = t = td.lifted.t + 0.01;
      back.contact = {true, true};
      w.torques(back);
    }
    REQUIRE(w.phase() == WalkerPhase::DoubleSupport);
    Vec5 q, qd;
    ssState(mo, mo.q_iSS(0) + 0.01 * (mo.alpha_fSS - mo.q_iSS(0)), mo.alphadot_iSS, q, qd);
    w.torques(measured(g.model, q, qd, Stance::Right, 0.3, {true, true}, t + after));
    return w.phase();
  };
  CHECK(phase_on_rate(0.0, 0.5 * mo.T_DS) == WalkerPhase::SingleSupport);
  CHECK(phase_on_rate(0.035, 0.5 * mo.T_DS) == WalkerPhase::DoubleSupport);
  CHECK(phase_on_rate(0.035, 1.01 * mo.T_DS) == WalkerPhase::SingleSupport);
}

TEST_CASE("Walker moves the next swing foot's end onto the slope measured at the touchdown",
          "[control][walker][slope]") {
  const DefaultGait g;
  const GaitMotion<double>& mo = g.evaluation.motion;
  const WalkerOptions o = walkerOptionsFor(g.gait.options, g.model);
  // The swing outputs' shift at the end of the single support after a touchdown on ground
  // inclined by gamma, against the offset of the slope the touchdown measures.
  const auto check = [&](double gamma, double shortening) {
    Walker w(g.model, g.evaluation, g.gait.options.parameterisation, o);
    w.torques(w.initialState());
    Vec5 q, qd;
    ssState(mo, mo.alpha_fSS, mo.alphadot_fSS, q, qd);
    q.tail<2>() += slopeSwingOffset(g.model, mo, gamma).tail<2>();
    const double measured_slope = groundSlopeBetweenFeet(g.model, q);
    w.torques(measured(g.model, q, qd, Stance::Left, 0.0, {true, true}, 0.6));
    // The rear foot off 30 ms later at the gait's start state: the single support starts.
    ssState(mo, mo.q_iSS(0), mo.alphadot_iSS, q, qd);
    w.torques(measured(g.model, q, qd, Stance::Right, 0.3, {false, true}, 0.63));
    REQUIRE(w.phase() == WalkerPhase::SingleSupport);
    ssState(mo, mo.alpha_fSS, mo.alphadot_fSS, q, qd);
    const Vec4 error =
        w.torques(measured(g.model, q, qd, Stance::Right, 0.3, {false, true}, 1.2)).law.error;
    const Vec4 offset = slopeSwingOffset(g.model, mo, measured_slope, shortening);
    CHECK(offset.tail<2>().norm() > 0.01);
    CHECK((error.tail<2>() + offset.tail<2>()).norm() < 1e-9);
  };
  check(0.035, 0.0);
  check(-0.035, kDownhillShortening);
}

}  // namespace gaitopt::test
