// Poincaré Jacobian by the variational equations: a passive rimless wheel whose map Jacobian is
// known in closed form (event saltation and impact reset exercised), and the closed-loop
// walking map against central finite differences of the simulated map.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "gaitopt/sim/poincare_sensitivity.hpp"
#include "test_default_gait.hpp"

namespace gaitopt::test {

TEST_CASE("Rimless wheel: sensitivity Jacobian of the step map equals the analytic one",
          "[sim][poincare][sensitivity]") {
  // Stance θ̈ = (g/l) sin θ from θ0 = γ − β to the touchdown θ = γ + β; impact θ⁺ = θ − 2β,
  // θ̇⁺ = cos(2β) θ̇. Energy gives θ̇⁻² = θ̇0² + 2(g/l)(cos θ0 − cos(γ + β)), so at the fixed
  // point θ̇*² = c² 4(g/l) sin γ sin β / (1 − c²), c = cos 2β, the Jacobian is
  // [[0, 0], [−c² (g/l) sin θ0 / θ̇*, c²]]: eigenvalues 0 and c².
  const double gl = 9.81, beta = M_PI / 8, gamma = 0.08, c = std::cos(2 * beta);
  const double w_star = std::sqrt(c * c * 4 * gl * std::sin(gamma) * std::sin(beta) / (1 - c * c));
  HybridPhase stance;
  stance.field = [gl](double, const Eigen::VectorXd& x, Eigen::VectorXd& f) {
    f = Eigen::Vector2d(x(1), gl * std::sin(x(0)));
  };
  stance.event = [&](const Eigen::VectorXd& x) { return gamma + beta - x(0); };
  const Eigen::Vector2d x0(gamma - beta, w_star);
  const PhaseEnd end =
      flowWithSensitivity(stance, {0.0, x0, Eigen::Matrix2d::Identity()}, 10.0, {1e-12, 1e-14});
  REQUIRE(end.event);
  const Eigen::Matrix2d reset = Eigen::Vector2d(1.0, c).asDiagonal();
  const Eigen::Vector2d next = reset * end.state.x - Eigen::Vector2d(2 * beta, 0.0);
  const Eigen::Matrix2d J = reset * end.state.S;
  CHECK((next - x0).norm() < 1e-10);  // the analytic fixed point
  Eigen::Matrix2d expected;
  expected << 0.0, 0.0, -c * c * gl * std::sin(x0(0)) / w_star, c * c;
  CHECK((J - expected).cwiseAbs().maxCoeff() < 1e-8);
  const PoincareLinearisation L = analyseJacobian(J);
  CHECK(std::abs(L.eigenvalues(0) - c * c) < 1e-8);
  CHECK(std::abs(L.eigenvalues(1)) < 1e-8);
}

TEST_CASE("Walking map: sensitivity Jacobian agrees with central finite differences",
          "[sim][poincare][sensitivity]") {
  const DefaultGait f;
  WalkRequest req;
  req.torque_limits = false;  // the smooth (unsaturated) closed loop: see docs/commands/stability.md
  req.tolerances = {1e-12, 1e-14};
  const Eigen::VectorXd x = walkingCycleState(f.evaluation.motion);
  const Eigen::VectorXd h = Eigen::VectorXd::Constant(10, 1e-4);
  SECTION("low bandwidth: an O(1) Jacobian") {
    // At 8 rad/s output errors remain after one step, so the entries are O(1) and the
    // comparison is a real one. The simulated map (walkingStepMap) then stops perturbed starts
    // whose swing foot grazes the ground before α_fSS, so the differences are taken on the
    // same hybrid map without the ground check: the step map of the sensitivity run.
    // Perturbed touchdowns then have small foot speeds (< 1 mm/s): mapped by the relabelling.
    req.bandwidth = 8.0;
    const TouchdownMap td = impulseFreeTouchdown(1e-2);
    const StepSensitivity s = walkingStepSensitivity(f.evaluation, f.model, f.model, req, x, td);
    CHECK((s.x_next - x).lpNorm<Eigen::Infinity>() < 1e-9);
    const StepMap P = [&](const Eigen::VectorXd& y) {
      return walkingStepSensitivity(f.evaluation, f.model, f.model, req, y, td, false).x_next;
    };
    // Richardson: (4 D(h/2) − D(h)) / 3 removes the O(h²) error of the central differences.
    // The sanitizer pass checks three columns (α, α̇, δ̇4) instead of all ten.
    auto column = [&](Eigen::Index i, double step) {
      const Eigen::VectorXd e = step * Eigen::VectorXd::Unit(10, i);
      return Eigen::VectorXd((P(x + e) - P(x - e)) / (2.0 * step));
    };
    const std::vector<Eigen::Index> columns =
        lightTests() ? std::vector<Eigen::Index>{0, 5, 9}
                     : std::vector<Eigen::Index>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
    Eigen::MatrixXd fd = s.jacobian;
    for (Eigen::Index i : columns) fd.col(i) = (4.0 * column(i, h(i) / 2) - column(i, h(i))) / 3.0;
    const double scale = fd.cwiseAbs().maxCoeff();
    const double error = (s.jacobian - fd).cwiseAbs().maxCoeff();
    INFO("max |J| " << scale << ", max |J_sens - J_fd| " << error);
    CHECK(scale > 0.1);
    CHECK(error < 1e-6 * scale);
    const PoincareLinearisation L = analyseJacobian(s.jacobian);
    CHECK(std::abs(L.eigenvalues(0)) < 1.0);
    if (!lightTests())
      CHECK(std::abs(std::abs(L.eigenvalues(0)) - std::abs(analyseJacobian(fd).eigenvalues(0))) <
            1e-6 * scale);
  }
  SECTION("default bandwidth: against the simulated map") {
    const StepMap P = walkingStepMap(f.evaluation, f.model, f.model, req);
    const PoincareLinearisation L =
        linearisePoincareBySensitivity(f.evaluation, f.model, f.model, req, x);
    const Eigen::MatrixXd fd = finiteDifferenceJacobian(P, x, h);
    CHECK(L.fixed_point_residual < 1e-9);
    // Every entry is below 1e-6 here: the check is at the accuracy of both, the differences'
    // noise (a map error of ~1e-11 over the step 1e-4) and the sensitivities' absolute
    // tolerance (1e-8 per CVODE step, over the few hundred steps of a walking step).
    CHECK((L.jacobian - fd).cwiseAbs().maxCoeff() < 1e-6);
    CHECK(std::abs(L.eigenvalues(0)) < 1e-7);
  }
}

}  // namespace gaitopt::test
