// Touchdown by swing-foot height for a zero-velocity gait (references held past α_fSS, plastic
// impact with both feet held, then the DS), the push margins it gives the default gait, and
// the plant on inclined ground.
#include <catch2/catch.hpp>

#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/forward_dynamics.hpp"
#include "gaitopt/sim/hybrid_walk.hpp"
#include "gaitopt/sim/impact_touchdown.hpp"
#include "gaitopt/sim/poincare.hpp"
#include "gaitopt/sim/stability_margins.hpp"
#include "test_default_gait.hpp"
#include "test_support.hpp"
#include "test_walk_request.hpp"

namespace gaitopt::test {
namespace {

// Foot 2 relative to foot 1 at the touchdown of step k (world frame), from the samples.
Vec2 touchdownFoot(const Model& m, const WalkResult& r, int k) {
  for (const WalkSample& s : r.samples)
    if (s.step == k && s.single_support && s.t == r.steps[k].t_touchdown)
      return chainPoint(m.pinned.foot2, chainState(m, s.q, s.qd));
  FAIL("no touchdown sample for step " << k);
  return Vec2::Zero();
}

}  // namespace

TEST_CASE("Zero-velocity gait, touchdown by foot height: the nominal cycle is kept", "[sim]") {
  const DefaultGait f;
  const GaitMotion<double>& mo = f.evaluation.motion;
  const WalkRequest req = gaitRequest(f.gait.options, lightTests() ? 2 : 3);
  REQUIRE(req.touchdown_by_foot_height);
  REQUIRE(req.hold_references_past_fss);
  const WalkResult r = simulateWalk(f.evaluation, f.model, f.model, req,
                                    gaitTouchdown(f.gait.options, "auto", 0.8));
  INFO(r.message);
  REQUIRE(r.outcome == WalkOutcome::Completed);
  for (const WalkStep& s : r.steps) {
    CHECK(s.alphad_start == Approx(mo.alphadot_iSS).margin(1e-8));
    CHECK(s.t_touchdown - s.t_start == Approx(mo.T_SS).margin(1e-4));
    CHECK(std::abs(touchdownFoot(f.model, r, s.step)(1)) <= 1e-12);
    CHECK(s.touchdown_foot_speed < 1e-5);  // it only grazes the ground
    CHECK(s.impact_behaviour == "held/stick");
    CHECK(s.double_support);
    CHECK(s.impact_energy_loss < 1e-9);
    CHECK(std::abs(stepEnergyBalanceError(s)) <= 1e-8);
  }
}

TEST_CASE("Zero-velocity gait pushed: the foot lands with an impact, the walk recovers",
          "[sim][stability]") {
  const DefaultGait f;
  WalkRequest req = gaitRequest(f.gait.options, 2);
  const TouchdownMap td = doubleSupportTouchdown(0.8, true);
  MarginRequest mr;
  mr.steps = lightTests() ? 3 : 5;
  mr.tolerance = lightTests() ? 0.05 : 1e-3;
  std::string why;
  for (const double dv : {0.1, -0.1}) {
    DYNAMIC_SECTION("hip velocity change " << dv << " m/s at mid SS") {
      CHECK(pushRecovered(f.evaluation, f.model, req, dv, mr, td, why));
      INFO(why);
    }
  }
  SECTION("a late touchdown (ground falling 0.02 rad): located by foot height, with impact") {
    req.ground_slope = -0.02;  // the outputs have converged by then: only the ground moves
    const WalkResult r = simulateWalk(f.evaluation, f.model, f.model, req, td);
    INFO(r.message);
    REQUIRE(r.outcome == WalkOutcome::Completed);
    const WalkStep& s = r.steps[0];
    CHECK(s.touchdown_foot_speed > 1e-3);
    CHECK(s.touchdown_event_residual <= 1e-9);
    CHECK(s.impact_energy_loss > 0.0);
    CHECK(s.impulse2(1) > 0.0);
    CHECK(std::abs(stepEnergyBalanceError(s)) <= 1e-8);
  }
}

TEST_CASE("Held impact: both feet at rest after it, momentum and energy consistent", "[sim]") {
  const DefaultGait f;
  const GaitMotion<double>& mo = f.evaluation.motion;
  // The pre-touchdown state with a downward foot velocity: the cycle's, q*(α_fSS) α̇_fSS (foot at
  // rest), plus a rotation about the stance foot (α̇ only), as the held references give.
  Vec5 qd;
  qd(0) = 1.0;
  for (int j = 0; j < 4; ++j) qd(j + 1) = mo.ss_path[j](mo.alpha_fSS).first;
  qd *= mo.alphadot_fSS;
  qd(0) -= 0.05;
  const TouchdownResult td = doubleSupportTouchdown(0.8, false)(f.model, mo.q_fSS, qd);
  REQUIRE(td.ok);
  CHECK(td.behaviour == "held/stick");
  CHECK(td.double_support_follows);
  // After the relabelling the new foot 2 (old stance foot) is at rest, and so is the new foot 1.
  CHECK((pinnedTerms(f.model, td.q_plus, td.qd_plus).D2 * td.qd_plus).norm() <= 1e-12);
  const double loss = pinnedEnergy(f.model, mo.q_fSS, qd) - pinnedEnergy(f.model, td.q_plus,
                                                                         td.qd_plus);
  CHECK(loss == Approx(td.energy_loss).epsilon(1e-10));
  CHECK(td.energy_loss > 0.0);
}

TEST_CASE("Inclined ground: zero slope is the flat plant, the feet land on the incline",
          "[sim][stability]") {
  const DefaultGait f;
  WalkRequest req = gaitRequest(f.gait.options, lightTests() ? 2 : 3);
  const TouchdownMap td = doubleSupportTouchdown(0.8, true);
  const WalkResult flat = simulateWalk(f.evaluation, f.model, f.model, req, td);
  req.ground_slope = -0.0;
  const WalkResult zero = simulateWalk(f.evaluation, f.model, f.model, req, td);
  REQUIRE(zero.samples.size() == flat.samples.size());
  for (std::size_t i = 0; i < flat.samples.size(); ++i)
    CHECK((zero.samples[i].q - flat.samples[i].q).lpNorm<Eigen::Infinity>() == 0.0);
  for (const double slope : {-0.03, 0.0005}) {
    DYNAMIC_SECTION("slope " << slope << " rad") {
      req.ground_slope = slope;
      const WalkResult r = simulateWalk(f.evaluation, f.model, f.model, req, td);
      INFO(r.message);
      REQUIRE(r.outcome == WalkOutcome::Completed);
      for (const WalkStep& s : r.steps) {
        const Vec2 foot = touchdownFoot(f.model, r, s.step);
        CHECK(foot(1) == Approx(foot(0) * std::tan(slope)).margin(1e-9));
        // Gravity stays vertical in the world frame: the balance holds with it.
        CHECK(std::abs(stepEnergyBalanceError(s)) <= 1e-8);
      }
      // Downhill the foot lands later (lower), uphill earlier.
      CHECK((r.steps[0].t_touchdown - flat.steps[0].t_touchdown) * slope < 0.0);
    }
  }
  SECTION("the slope margin's test: down 0.03 rad walks, down 0.3 rad does not") {
    MarginRequest mr;
    mr.steps = lightTests() ? 2 : 5;
    std::string why;
    CHECK(slopeWalked(f.evaluation, f.model, req, -0.03, mr, td, why));
    CHECK_FALSE(slopeWalked(f.evaluation, f.model, req, -0.3, mr, td, why));
    CHECK_THAT(why, Catch::Matchers::Contains("step"));
  }
}

}  // namespace gaitopt::test
