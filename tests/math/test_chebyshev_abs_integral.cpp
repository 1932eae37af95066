// ∫|p| and ∫max(0, p) of a Chebyshev interpolant split at its sign changes
// (math/chebyshev_abs_integral.hpp): values against closed forms, the roots, a pair of roots
// between two nodes, and the derivatives through AD against the closed-form derivatives.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "gaitopt/math/chebyshev_abs_integral.hpp"

namespace {

using gaitopt::ChebyshevGrid;
using AD1 = Eigen::AutoDiffScalar<Eigen::Matrix<double, 1, 1>>;

template <class F> Eigen::VectorXd nodalValues(const ChebyshevGrid& grid, const F& f) {
  Eigen::VectorXd v(grid.size());
  for (int k = 0; k < grid.size(); ++k) v[k] = f(grid.nodes()[k]);
  return v;
}

}  // namespace

TEST_CASE("chebyshev: cumulativeAt integrates the interpolant from +1 to any point",
          "[math][kinks]") {
  const ChebyshevGrid grid(16);
  for (int k = 0; k < grid.size(); ++k)
    CHECK((grid.cumulativeAt(grid.nodes()[k]) - grid.cumulative().row(k)).cwiseAbs().maxCoeff() <
          1e-14);
  const Eigen::VectorXd cube = nodalValues(grid, [](double s) { return s * s * s; });
  for (double s : {-1.0, -0.731, 0.0, 0.2, 0.999})
    CHECK(grid.cumulativeAt(s).dot(cube) == Approx((s * s * s * s - 1.0) / 4.0).margin(1e-15));
}

TEST_CASE("chebyshev: integrateAbs splits at the roots, exact for the interpolant",
          "[math][kinks]") {
  const ChebyshevGrid grid(32);
  std::vector<double> roots;
  // s² − 1/4: roots ±1/2, ∫|p| = 1/2, ∫max(0, p) = 1/3.
  const Eigen::VectorXd quad = nodalValues(grid, [](double s) { return s * s - 0.25; });
  CHECK(gaitopt::integrateAbs(grid, quad, roots) == Approx(0.5).margin(1e-15));
  REQUIRE(roots.size() == 2);
  CHECK(roots[0] == Approx(0.5).margin(1e-15));  // decreasing s
  CHECK(roots[1] == Approx(-0.5).margin(1e-15));
  roots.clear();
  CHECK(gaitopt::integratePositivePart(grid, quad, roots) == Approx(1.0 / 3.0).margin(1e-15));

  // sin 5s (not a polynomial): roots 0, ±π/5; spectral accuracy, where the Clenshaw–Curtis sum
  // of |f_k| is off at the third digit.
  roots.clear();
  const Eigen::VectorXd sine = nodalValues(grid, [](double s) { return std::sin(5.0 * s); });
  const double exact = 2.0 * (0.4 + (std::cos(5.0) + 1.0) / 5.0);
  CHECK(gaitopt::integrateAbs(grid, sine, roots) == Approx(exact).margin(1e-13));
  CHECK(roots.size() == 3);
  CHECK(std::abs(grid.weights().dot(sine.cwiseAbs()) - exact) > 1e-4);
  // No sign change: the plain quadrature, bit for bit.
  roots.clear();
  const Eigen::VectorXd positive = nodalValues(grid, [](double s) { return 2.0 + s; });
  CHECK(gaitopt::integrateAbs(grid, positive, roots) ==
        gaitopt::integrateReference(grid, positive));
  CHECK(roots.empty());
}

TEST_CASE("chebyshev: a pair of roots between two nodes is found", "[math][kinks]") {
  const ChebyshevGrid grid(32);
  // (s − c)² − ε² with both roots strictly between nodes 10 and 11, where the nodal values are
  // all positive: found from the sign change of p′ around the minimum.
  const double c = 0.5 * (grid.nodes()[10] + grid.nodes()[11]), eps = 0.01;
  REQUIRE(grid.nodes()[10] - grid.nodes()[11] > 2.0 * eps);
  const Eigen::VectorXd v =
      nodalValues(grid, [c, eps](double s) { return (s - c) * (s - c) - eps * eps; });
  REQUIRE(v.minCoeff() > 0.0);
  std::vector<double> roots;
  const double integral = gaitopt::integrateAbs(grid, v, roots);
  REQUIRE(roots.size() == 2);
  CHECK(roots[0] == Approx(c + eps).margin(1e-14));
  CHECK(roots[1] == Approx(c - eps).margin(1e-14));
  // ∫|p| = ∫p + 2·(4/3)ε³, the lobe below zero counted positive.
  const auto antiderivative = [c, eps](double s) {
    return (s - c) * (s - c) * (s - c) / 3.0 - eps * eps * s;
  };
  const double plain = antiderivative(1.0) - antiderivative(-1.0);
  CHECK(integral == Approx(plain + 8.0 / 3.0 * eps * eps * eps).epsilon(1e-14));
}

TEST_CASE("chebyshev: derivatives of integrateAbs and of its roots through AD",
          "[math][kinks]") {
  const ChebyshevGrid grid(24);
  // p(s) = s² − θ²: ∫|p| = 2 (4θ³/3 − θ² + 1/3), roots ±θ, for 0 < θ < 1.
  for (double theta : {0.3, 0.55, 0.81}) {
    const AD1 t(theta, 1, 0);
    Eigen::Matrix<AD1, Eigen::Dynamic, 1> v(grid.size());
    for (int k = 0; k < grid.size(); ++k) v[k] = grid.nodes()[k] * grid.nodes()[k] - t * t;
    std::vector<AD1> roots;
    const AD1 integral = gaitopt::integrateAbs(grid, v, roots);
    CHECK(integral.value() ==
          Approx(2.0 * (4.0 / 3.0 * theta * theta * theta - theta * theta + 1.0 / 3.0))
              .margin(1e-14));
    CHECK(integral.derivatives()(0) ==
          Approx(2.0 * (4.0 * theta * theta - 2.0 * theta)).margin(1e-13));
    REQUIRE(roots.size() == 2);
    CHECK(roots[0].value() == Approx(theta).margin(1e-15));
    CHECK(roots[0].derivatives()(0) == Approx(1.0).margin(1e-13));
    CHECK(roots[1].derivatives()(0) == Approx(-1.0).margin(1e-13));
  }
}
