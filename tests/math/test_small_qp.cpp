// Least-distance QP of the constrained control law: hand-solved projections, infeasibility,
// and optimality against random feasible points.
#include <catch2/catch.hpp>
#include <random>

#include "gaitopt/math/small_qp.hpp"

namespace gaitopt::test {

TEST_CASE("Small QP: hand-solved weighted projections", "[sim][qp]") {
  Eigen::MatrixXd G(3, 2);
  G << 1, 1, -1, 0, 0, -1;  // x1 + x2 ≤ 1, x ≥ 0
  const Eigen::Vector3d h(1, 0, 0);
  // Projection of x0 with weights w: the expected point and number of active constraints.
  auto check = [&](const Eigen::Vector2d& w, const Eigen::Vector2d& x0, int active,
                   const Eigen::Vector2d& expected) {
    const SmallQpResult r = solveLeastDistanceQp(G, h, w, x0);
    REQUIRE(r.feasible);
    CHECK(r.active == active);
    CHECK((r.x - expected).cwiseAbs().maxCoeff() < 1e-12);
  };
  SECTION("equal weights: onto the face x1 + x2 = 1") {
    check(Eigen::Vector2d(1, 1), Eigen::Vector2d(2, 2), 1, Eigen::Vector2d(0.5, 0.5));
  }
  SECTION("weights (1, 4): the corner (0, 1), x1 ≥ 0 with multiplier 4") {
    check(Eigen::Vector2d(1, 4), Eigen::Vector2d(2, 2), 2, Eigen::Vector2d(0.0, 1.0));
  }
  SECTION("a feasible x0 is returned unchanged") {
    check(Eigen::Vector2d(1, 1), Eigen::Vector2d(0.2, 0.3), 0, Eigen::Vector2d(0.2, 0.3));
  }
  SECTION("x1 ≤ −1 and x1 ≥ 0: infeasible") {
    Eigen::MatrixXd G2(2, 2);
    G2 << 1, 0, -1, 0;
    const SmallQpResult r = solveLeastDistanceQp(G2, Eigen::Vector2d(-1, 0), Eigen::Vector2d(1, 1),
                                                 Eigen::Vector2d(1, 1));
    CHECK_FALSE(r.feasible);
  }
}

TEST_CASE("Small QP: 4 variables, 14 rows: no random feasible point does better", "[sim][qp]") {
  std::mt19937 rng(11);
  std::normal_distribution<double> n01;
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::MatrixXd G(14, 4);
    for (Eigen::Index i = 0; i < G.size(); ++i) G(i) = n01(rng);
    const Eigen::VectorXd h = Eigen::VectorXd::Ones(14);  // x = 0 feasible
    Eigen::Vector4d x0, w;
    for (int i = 0; i < 4; ++i) {
      x0(i) = 3.0 * n01(rng);
      w(i) = 0.5 + std::abs(n01(rng));
    }
    const SmallQpResult r = solveLeastDistanceQp(G, h, w, x0);
    REQUIRE(r.feasible);
    CHECK((G * r.x - h).maxCoeff() <= 1e-9);
    const auto cost = [&](const Eigen::Vector4d& x) { return (x - x0).cwiseAbs2().dot(w); };
    const double best = cost(r.x);
    for (int k = 0; k < 2000; ++k) {
      Eigen::Vector4d x;
      for (int i = 0; i < 4; ++i) x(i) = r.x(i) + 0.3 * n01(rng);
      if ((G * x - h).maxCoeff() <= 0.0) CHECK(cost(x) >= best - 1e-12);
    }
  }
}

}  // namespace gaitopt::test
