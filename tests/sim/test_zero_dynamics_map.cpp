// Zero-dynamics Poincaré map (§4.2.2) of the default gait's closed loop, and the stability
// margins found by bisection.
#include <catch2/catch.hpp>
#include <cmath>

#include "gaitopt/sim/stability_margins.hpp"
#include "gaitopt/sim/zero_dynamics_map.hpp"
#include "test_default_gait.hpp"

namespace gaitopt::test {

// The analysis' closed loop: without the (non-smooth) torque projection, docs/commands/stability.md.
WalkRequest smoothRequest() {
  WalkRequest req;
  req.torque_limits = false;
  return req;
}

TEST_CASE("Zero-dynamics map: the gait's cycle is a fixed point reached in one step",
          "[sim][poincare][zero_dynamics]") {
  const DefaultGait f;
  const WalkRequest req = smoothRequest();
  ZeroDynamicsRequest zr;
  zr.range = 0.015;
  zr.points = 7;  // starts α̇* (1 + 0.005 k), k = −3..3
  const ZeroDynamicsStudy z = studyZeroDynamics(f.evaluation, f.model, f.model, req, zr);
  CHECK(z.fixed_point == f.evaluation.motion.alphadot_iSS);
  CHECK(z.fixed_point_residual < 1e-9 * std::abs(z.fixed_point));
  // The DS control of α restores α̇_iSS at lift-off from any touchdown state it can track:
  // the map is flat (Theorem 4's one-step convergence).
  CHECK(std::abs(z.slope) < 1e-4);
  CHECK(z.stable);
  REQUIRE(z.points.size() == 7u);
  for (const ZeroDynamicsPoint& p : z.points) {
    INFO("start " << p.alphad_iSS << ", outcome " << p.outcome);
    CHECK(p.alphad_iDS < 0.0);
    if (p.outcome != "completed") {
      CHECK(p.steps_to_cycle == -1);
      continue;
    }
    CHECK(std::abs(p.next_alphad_iSS - z.fixed_point) < 1e-6 * std::abs(z.fixed_point));
    CHECK(p.steps_to_cycle <= 1);
  }
  // a: the SS + touchdown map is increasing in |α̇_iSS| (energy).
  for (std::size_t i = 1; i < 7; ++i) CHECK(z.points[i].alphad_iDS < z.points[i - 1].alphad_iDS);
  // Slower starts are caught; 1.5 % too fast, the cubic DS law lifts a foot while braking.
  CHECK(z.points.front().outcome == "completed");
  CHECK(z.points.back().outcome == "stance_lift_off");
  CHECK(z.one_step_high == z.points.front().alphad_iSS);
  CHECK(z.one_step_low <= z.fixed_point);
  CHECK(z.one_step_low > z.points.back().alphad_iSS);
  CHECK(z.global_low == z.one_step_low);
  CHECK(z.resolution == Approx(0.03 * std::abs(z.fixed_point) / 6));
}

TEST_CASE("Push margin: the bisection brackets the largest recovered push",
          "[sim][poincare][margins]") {
  MarginRequest mr;
  mr.push_upper = 0.5;
  const DefaultGait f;
  const WalkRequest req = smoothRequest();
  mr.push_resolution = 2e-3;
  std::string why;
  // With the impulse-free touchdown any push that leaves an output error at touchdown fails.
  CHECK(pushRecovered(f.evaluation, f.model, req, 0.0, mr, impulseFreeTouchdown(), why));
  CHECK_FALSE(pushRecovered(f.evaluation, f.model, req, 0.05, mr, impulseFreeTouchdown(), why));
  CHECK_THAT(why, Catch::Matchers::Contains("impact_model_unavailable"));
  // Touchdowns up to 5 mm/s accepted as impulse-free: the margin of the controller alone.
  const TouchdownMap lenient = impulseFreeTouchdown(5e-3);
  const Margin m = largestPush(f.evaluation, f.model, req, 1, mr, lenient);
  INFO("forward push margin " << m.value << " m/s, limit " << m.limit);
  CHECK_FALSE(m.bracket_reached);
  CHECK(m.value > 0.0);
  CHECK(m.resolution == mr.push_resolution);
  CHECK(pushRecovered(f.evaluation, f.model, req, m.value, mr, lenient, why));
  CHECK_FALSE(pushRecovered(f.evaluation, f.model, req, m.value + 2 * mr.push_resolution, mr,
                            lenient, why));
}

}  // namespace gaitopt::test
