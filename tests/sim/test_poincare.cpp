// Poincaré analysis: a passive linear system whose map eigenvalues are known exactly, and the
// closed-loop walking cycle of the default gait (a fixed point, stable, one-step convergent α̇).
#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>

#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/sim/poincare.hpp"
#include "test_default_gait.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

TEST_CASE("Poincaré map of a passive damped oscillator has eigenvalues exp(lambda T)",
          "[sim][poincare]") {
  // ẍ + 3ẋ + 2x = 0: λ = −1, −2; the time-T map is exp(A T), eigenvalues e^{−T}, e^{−2T}.
  Eigen::Matrix2d A;
  A << 0, 1, -2, -3;
  const double T = 0.7;
  CvodeIntegrator cv(
      2, [&A](double, const Eigen::VectorXd& y, Eigen::VectorXd& f) { f = A * y; }, 0,
      [](double, const Eigen::VectorXd&, Eigen::VectorXd&) {}, {1e-12, 1e-14});
  const StepMap P = [&](const Eigen::VectorXd& x) {
    cv.reset(0.0, x);
    return cv.advance(T).y;
  };
  const Eigen::VectorXd origin = Eigen::VectorXd::Zero(2);
  const PoincareLinearisation L = linearisePoincare(P, origin, Eigen::VectorXd::Constant(2, 1e-3));
  CHECK(L.fixed_point_residual == 0.0);
  CHECK(L.eigenvalues(0).real() == Approx(std::exp(-T)).margin(1e-8));
  CHECK(L.eigenvalues(1).real() == Approx(std::exp(-2 * T)).margin(1e-8));
  CHECK(L.eigenvalues.imag().norm() == 0.0);
  const Eigen::EigenSolver<Eigen::Matrix2d> es(A);
  const Eigen::Matrix2cd V = es.eigenvectors();
  const Eigen::Matrix2cd expAT =
      V * (es.eigenvalues() * T).array().exp().matrix().asDiagonal() * V.inverse();
  CHECK((L.jacobian - expAT.real()).norm() < 1e-8);
  Eigen::VectorXd v;
  CHECK(powerIteration(P, origin, Eigen::VectorXd::Constant(2, 1e-3), 30, v) ==
        Approx(std::exp(-T)).epsilon(1e-6));
  CHECK(std::abs(v.normalized().dot(Eigen::Vector2d(1, -1).normalized())) ==
        Approx(1.0).epsilon(1e-6));  // eigenvector of λ = −1
}

TEST_CASE("Closed-loop walking cycle of the default gait is a stable fixed point",
          "[sim][poincare]") {
  const DefaultGait f;
  WalkRequest req;
  req.tolerances = {1e-12, 1e-14};
  const StepMap P = walkingStepMap(f.evaluation, f.model, f.model, req);
  const Eigen::VectorXd x = walkingCycleState(f.evaluation.motion);
  const PoincareLinearisation L = linearisePoincare(P, x, Eigen::VectorXd::Constant(10, 1e-4));
  CHECK(L.fixed_point_residual < 1e-9);
  // Outputs decay as e^{−ω T_SS} ≈ 1e-10 and the DS control of α is deadbeat: every
  // eigenvalue is at the finite-difference noise level.
  CHECK(std::abs(L.eigenvalues(0)) < 1e-6);
  CHECK(std::abs(L.jacobian(5, 5)) < 1e-6);  // ∂α̇⁺/∂α̇: one-step convergence
  CHECK_THROWS_WITH(P(Eigen::VectorXd(x + 0.2 * Eigen::VectorXd::Unit(10, 5))),
                    Catch::Matchers::Contains("walking step map"));
}

}  // namespace gaitopt::test
