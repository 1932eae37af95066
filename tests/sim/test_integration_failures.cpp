// What the closed-loop analyses do when an integration cannot go on or a foot would slip: CVODE's
// failure as an IntegrationError (time and CVODE's own message), a walk ending as
// `integration_failed`, the Poincaré Jacobian falling back to central differences, and the
// stability map holding the feet where the planned friction cone is active.
#include <catch2/catch.hpp>
#include <cmath>

#include "gaitopt/sim/impact_touchdown.hpp"
#include "gaitopt/sim/poincare.hpp"
#include "gaitopt/sim/poincare_sensitivity.hpp"
#include "test_default_gait.hpp"
#include "test_walk_request.hpp"

namespace gaitopt::test {

TEST_CASE("CVODE: an integration that cannot go on throws IntegrationError with CVODE's message",
          "[sim]") {
  // ẏ = y², y(0) = 1: y = 1/(1 − t) blows up at t = 1.
  CvodeIntegrator cv(
      1, [](double, const Eigen::VectorXd& y, Eigen::VectorXd& f) { f = y.cwiseAbs2(); }, 0,
      [](double, const Eigen::VectorXd&, Eigen::VectorXd&) {}, {1e-10, 1e-12});
  cv.reset(0.0, Eigen::VectorXd::Ones(1));
  CHECK(cv.advance(0.5).y(0) == Approx(2.0).epsilon(1e-8));
  try {
    cv.advance(2.0);
    FAIL("CVODE integrated through the blow-up");
  } catch (const IntegrationError& e) {
    CHECK(e.time() > 0.999);
    CHECK(e.time() < 1.0);
    // CVODE's own text, not its flag number.
    CHECK_THAT(e.what(), Catch::Matchers::StartsWith("CVODE stopped at t = 1.000000 s: "));
    CHECK_THAT(e.what(), Catch::Matchers::Contains("mxstep steps taken before reaching tout"));
  }
}

TEST_CASE("Closed loop: a step CVODE cannot integrate ends the walk as integration_failed",
          "[sim]") {
  const DefaultGait f;
  WalkRequest req = gaitRequest(f.gait.options, 2);
  // A relative tolerance below the unit round-off: CVODE refuses the first step.
  req.tolerances = {1e-30, 1e-30};
  const WalkResult r = simulateWalk(f.evaluation, f.model, f.model, req);
  CHECK(r.outcome == WalkOutcome::IntegrationFailed);
  CHECK(std::string(outcomeName(r.outcome)) == "integration_failed");
  CHECK_THAT(r.message, Catch::Matchers::StartsWith("CVODE stopped at t = 0"));
  CHECK_THAT(r.message, Catch::Matchers::EndsWith("step 0 at t = 0.000000 s"));
}

TEST_CASE("Poincaré: variational equations CVODE cannot integrate give way to differences",
          "[sim][poincare]") {
  // The time-0.7 map of ẍ + 3ẋ + 2x = 0.
  Eigen::Matrix2d A;
  A << 0, 1, -2, -3;
  CvodeIntegrator cv(
      2, [&A](double, const Eigen::VectorXd& y, Eigen::VectorXd& f) { f = A * y; }, 0,
      [](double, const Eigen::VectorXd&, Eigen::VectorXd&) {}, {1e-12, 1e-14});
  const StepMap P = [&](const Eigen::VectorXd& x) {
    cv.reset(0.0, x);
    return cv.advance(0.7).y;
  };
  const Eigen::VectorXd x = Eigen::VectorXd::Zero(2), h = Eigen::VectorXd::Constant(2, 1e-3);
  const PoincareLinearisation differences = linearisePoincare(P, x, h);
  std::string fallback;
  const PoincareLinearisation failed = linearisePoincareOrDifferences(
      []() -> PoincareLinearisation { throw IntegrationError(0.5, "CVODE stopped: test"); }, P,
      x, h, fallback);
  CHECK(fallback == "CVODE stopped: test");
  CHECK((failed.jacobian - differences.jacobian).norm() == 0.0);
  CHECK(failed.fixed_point_residual == differences.fixed_point_residual);
  // Variational equations that integrate are used as they are.
  PoincareLinearisation given;
  given.jacobian = Eigen::MatrixXd::Identity(2, 2);
  std::string none;
  const PoincareLinearisation used =
      linearisePoincareOrDifferences([&] { return given; }, P, x, h, none);
  CHECK(none.empty());
  CHECK(used.jacobian == given.jacobian);
}

TEST_CASE("Stability map: a cycle on its friction cone is perturbed with the feet held",
          "[sim][poincare]") {
  // The shipped impact gait's stance foot reaches its planned cone (μ 0.6) before touchdown:
  // the power iteration's perturbations (1e-4 on every state component, then along the
  // dominant direction) slip it there. Held, they give the dominant eigenvalue of the
  // variational equations (which hold the feet).
  const ShippedGait f("configs/gait/default_impact.yaml");
  WalkRequest req = gaitRequest(f.gait.options, 1);
  req.tolerances = {1e-12, 1e-14};
  req.torque_limits = false;
  req.touchdown_by_foot_height = true;
  req.hold_references_past_fss = false;
  const TouchdownMap td =
      gaitTouchdown(f.gait.options, "auto", f.gait.options.friction_coefficient);
  const Eigen::VectorXd x = walkingCycleState(f.evaluation.motion);
  const Eigen::VectorXd h = Eigen::VectorXd::Constant(10, 1e-4);
  Eigen::VectorXd v;
  CHECK_THROWS_WITH(powerIteration(walkingStepMap(f.evaluation, f.model, f.model, req, td), x,
                                   h, 6, v),
                    Catch::Matchers::Contains("slipped: stance foot left its friction cone"));
  const PoincareLinearisation L =
      linearisePoincareBySensitivity(f.evaluation, f.model, f.model, req, x, td);
  req.detect_slip = false;
  const double estimate =
      powerIteration(walkingStepMap(f.evaluation, f.model, f.model, req, td), x, h, 6, v);
  CHECK(std::abs(L.eigenvalues(0)) > 0.5);
  CHECK(estimate == Approx(std::abs(L.eigenvalues(0))).margin(1e-4));
}

}  // namespace gaitopt::test
