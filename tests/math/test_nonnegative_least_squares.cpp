// Non-negative least squares: a hand-solved case and the KKT conditions on random problems.
#include <catch2/catch.hpp>
#include <random>

#include "gaitopt/math/nonnegative_least_squares.hpp"

namespace gaitopt::test {

TEST_CASE("NNLS: hand-solved cases", "[math][nnls]") {
  // A = I: x = max(b, 0).
  const NnlsResult r = solveNonnegativeLeastSquares(Eigen::MatrixXd::Identity(2, 2),
                                                    Eigen::Vector2d(1.0, -1.0));
  CHECK(r.converged);
  CHECK(r.x(0) == Approx(1.0).margin(1e-14));
  CHECK(r.x(1) == 0.0);
  CHECK(r.residual == Approx(1.0).margin(1e-14));
  // Three columns for two equations, b in the cone of columns 0 and 2 only: b = 2 a0 + a2.
  Eigen::MatrixXd A(2, 3);
  A << 1, 0, 1,
       0, -1, 1;
  const NnlsResult cone = solveNonnegativeLeastSquares(A, Eigen::Vector2d(3.0, 1.0));
  CHECK(cone.converged);
  CHECK(cone.residual < 1e-12);
  CHECK(cone.x(0) == Approx(2.0).margin(1e-12));
  CHECK(cone.x(1) == Approx(0.0).margin(1e-12));
  CHECK(cone.x(2) == Approx(1.0).margin(1e-12));
}

TEST_CASE("NNLS: KKT conditions on random problems", "[math][nnls]") {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 50; ++trial) {
    const int m = 3 + trial % 6, n = 2 + trial % 9;  // over- and underdetermined
    Eigen::MatrixXd A(m, n);
    Eigen::VectorXd b(m);
    for (int i = 0; i < m; ++i) {
      b(i) = normal(rng);
      for (int j = 0; j < n; ++j) A(i, j) = normal(rng);
    }
    const NnlsResult r = solveNonnegativeLeastSquares(A, b);
    INFO("trial " << trial);
    REQUIRE(r.converged);
    // x ≥ 0; w = Aᵀ(b − Ax) ≤ 0, and = 0 where x > 0 (the optimality conditions).
    const Eigen::VectorXd w = A.transpose() * (b - A * r.x);
    const double scale = 1e-9 * (1.0 + (A.transpose() * b).cwiseAbs().maxCoeff());
    for (int j = 0; j < n; ++j) {
      CHECK(r.x(j) >= 0.0);
      CHECK(w(j) <= scale);
      if (r.x(j) > 0.0) CHECK(std::abs(w(j)) <= scale);
    }
    CHECK(r.residual == Approx((A * r.x - b).norm()));
  }
}

}  // namespace gaitopt::test
