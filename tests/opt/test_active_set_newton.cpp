// The active-set Newton closing of a stage (opt/active_set_newton.hpp): from a point next to
// an optimum whose speed and active constraints are slightly off, it returns a point meeting
// every constraint and the speed, a short distance away, at nearly the same criterion.
#include <catch2/catch.hpp>
#include <cmath>

#include "gaitopt/opt/active_set_newton.hpp"
#include "test_gait_support.hpp"

using namespace gaitopt;

TEST_CASE("active-set Newton closes a slightly infeasible optimum", "[optimize][closing]") {
  GaitOptions o = test::viscousOptions();
  o.target_speed = 0.5;
  const GaitEvaluator ev = test::defaultGaitEvaluator(o);
  GaitEvaluationCache cache(ev);
  const GaitParameters optimum = test::optimalStep();
  const double c0 = ev.evaluate(optimum).C_Gamma;
  // Off the speed by ~1e-5 m/s (as SLSQP leaves the richer Chesse runs), the active
  // constraints moved with it.
  GaitParameters p = optimum;
  p(kTDS) += 2e-5;
  p(kStepLength) -= 1e-5;
  REQUIRE(std::abs(ev.evaluate(p).speed - 0.5) > 5e-6);
  const ActiveSetClosing c = closeActiveSet(cache, p, Criterion::Torque, 0.5, 1e-6, 1e-6);
  CHECK(c.feasible);
  CHECK(c.iterations >= 1);
  CHECK(c.iterations <= 4);
  CHECK(c.active >= 2);  // the speed and at least one grid entry
  const GaitEvaluation<double> e = ev.evaluate(c.x);
  CHECK(std::abs(e.speed - 0.5) < 1e-9);
  CHECK(e.failed_level < 0);
  const GaitParameters D = parameterScales(ev.options().parameterisation);
  CHECK((c.x - p).cwiseQuotient(D).norm() < 1e-3);  // a Newton correction, not a new optimum
  CHECK(e.C_Gamma == Approx(c0).epsilon(1e-4));
  // Already feasible: nothing to do.
  const ActiveSetClosing same = closeActiveSet(cache, c.x, Criterion::Torque, 0.5, 1e-6, 1e-6);
  CHECK(same.feasible);
  CHECK((same.x - c.x).norm() < 1e-8);
}

// Regression (2026-11-23): the staged repair from α_fDS = α_iDS + 0.05 stalled SLSQP here,
// 1.13e-5 m/s off the speed with one friction-cone entry identically at its bound (a row
// left out of the Newton system). One step closed the speed to 1e-10 m/s; the next found no
// step lowering the violation (that entry keeps it at `interior`) and the closing was
// refused as "not feasible" where it had already met every constraint.
TEST_CASE("active-set Newton is judged where its steps stop", "[optimize][closing]") {
  GaitOptions o = test::viscousOptions();
  o.target_speed = 0.5;
  const GaitEvaluator ev = test::defaultGaitEvaluator(o);
  GaitEvaluationCache cache(ev);
  GaitParameters p(kNumGaitParameters);
  p << 0.02736988364, -2.66210881, 1.535558384, 0.3395393097, -0.03904245282, -2.603920144,
      1.482012079, -2.591035551, 1.525485439, 0.03330243037, 0.03052294374, -0.809636347,
      -0.2249259652, -0.4758097038, 0.09697310231, -0.2437600136, 0.05244282273;
  const GaitEvaluation<double> e0 = ev.evaluate(p);
  REQUIRE(e0.motion_computed);
  REQUIRE(std::abs(e0.speed - 0.5) > 1e-5);
  const ActiveSetClosing c = closeActiveSet(cache, p, Criterion::Torque, 0.5, 1e-6, 1e-6);
  CHECK(c.feasible);
  const GaitEvaluation<double> e = ev.evaluate(c.x);
  CHECK(std::abs(e.speed - 0.5) < 1e-9);
  CHECK(e.failed_level < 0);
  CHECK(e.C_Gamma == Approx(e0.C_Gamma).epsilon(1e-3));
}
