// Tests for the Chebyshev–Lobatto grid: quadrature, cumulative integration, interpolation,
// interval mapping and forward-mode AD through parameter-dependent end points.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "gaitopt/math/chebyshev.hpp"
#include "gaitopt/math/scalar.hpp"

namespace {

using gaitopt::ChebyshevGrid;
using AD2 = Eigen::AutoDiffScalar<Eigen::Vector2d>;

// Test integrand on x and its antiderivative; generic so it also runs on AD scalars.
template <class T>
T chebG(const T& x) {
  using std::cos;
  return cos(3.0 * x) + x * x;
}
double chebGAnti(double x) { return std::sin(3.0 * x) / 3.0 + x * x * x / 3.0; }

// Largest |error| seen per test, printed once so the report can quote the accuracy.
void reportMax(const char* what, double err) { std::printf("  [chebyshev] %-48s max err = %.3e\n", what, err); }

}  // namespace

TEST_CASE("chebyshev: nodes, sizes and barycentric weights", "[chebyshev]") {
  for (int n : {2, 3, 4, 7, 16, 32}) {
    const ChebyshevGrid grid(n);
    REQUIRE(grid.size() == n + 1);
    REQUIRE(grid.degree() == n);
    REQUIRE(grid.nodes()[0] == 1.0);
    REQUIRE(grid.nodes()[n] == -1.0);
    for (int k = 0; k <= n; ++k) {
      CHECK(grid.nodes()[k] == Approx(std::cos(M_PI * k / n)).margin(1e-15));
      CHECK(grid.nodes()[k] == -grid.nodes()[n - k]);  // exact symmetry
      if (k > 0) CHECK(grid.nodes()[k] < grid.nodes()[k - 1]);
      CHECK(std::abs(grid.barycentricWeights()[k]) == ((k == 0 || k == n) ? 0.5 : 1.0));
    }
  }
  REQUIRE_THROWS_AS(ChebyshevGrid(1), std::invalid_argument);
}

TEST_CASE("chebyshev: Clenshaw-Curtis weights", "[chebyshev]") {
  double worst_poly = 0.0;
  for (int n : {2, 3, 4, 5, 8, 15, 16, 32, 33}) {
    const ChebyshevGrid grid(n);
    const Eigen::VectorXd& s = grid.nodes();
    for (int d = 0; d <= n; ++d) {
      const double exact = (d % 2 == 0) ? 2.0 / (d + 1) : 0.0;
      const double approx = grid.weights().dot(s.array().pow(d).matrix());
      worst_poly = std::max(worst_poly, std::abs(approx - exact));
      CHECK(std::abs(approx - exact) < 1e-13);
    }
    // The last row of the cumulative matrix is ∫_{+1}^{-1} = -∫_{-1}^{1}.
    CHECK((grid.weights() + grid.cumulative().row(n).transpose()).cwiseAbs().maxCoeff() < 1e-14);
  }
  reportMax("weights: monomials deg <= n, n in 2..33", worst_poly);

  const ChebyshevGrid grid(32);
  const double approx = grid.weights().dot(grid.nodes().array().exp().matrix());
  const double err = std::abs(approx - (std::exp(1.0) - std::exp(-1.0)));
  reportMax("weights: exp(s), n = 32", err);
  CHECK(err < 1e-14);
}

TEST_CASE("chebyshev: cumulative integration matrix", "[chebyshev]") {
  const ChebyshevGrid grid(32);
  const Eigen::VectorXd& s = grid.nodes();
  const int np = grid.size();

  SECTION("reference interval, f = cos(3s) + s^2") {
    Eigen::VectorXd f(np);
    for (int k = 0; k < np; ++k) f[k] = chebG(s[k]);
    const Eigen::VectorXd qf = grid.cumulative() * f;
    REQUIRE(qf[0] == 0.0);
    double err = 0.0;
    for (int k = 0; k < np; ++k) err = std::max(err, std::abs(qf[k] - (chebGAnti(s[k]) - chebGAnti(1.0))));
    reportMax("cumulative: cos(3s)+s^2 on [-1,1], n = 32", err);
    CHECK(err < 1e-12);
    CHECK(qf[np - 1] < 0.0);  // integrating a positive function from +1 down to -1
  }

  SECTION("exact for polynomials of degree <= n") {
    for (int n : {2, 3, 6, 11}) {
      const ChebyshevGrid g(n);
      for (int d = 0; d <= n; ++d) {
        const Eigen::VectorXd f = g.nodes().array().pow(d).matrix();
        const Eigen::VectorXd qf = g.cumulative() * f;
        for (int k = 0; k <= n; ++k)
          CHECK(qf[k] == Approx((std::pow(g.nodes()[k], d + 1) - 1.0) / (d + 1)).margin(1e-14));
      }
    }
  }

  SECTION("mapped to a decreasing interval [a, b] = [0.3, -0.2]") {
    const double a = 0.3, b = -0.2;
    const Eigen::VectorXd x = gaitopt::mappedNodes(grid, a, b);
    REQUIRE(x[0] == a);
    REQUIRE(x[np - 1] == Approx(b).margin(1e-16));
    Eigen::VectorXd g(np);
    for (int k = 0; k < np; ++k) g[k] = chebG(x[k]);
    const double jac = gaitopt::intervalJacobian(a, b);
    REQUIRE(jac == Approx(0.25));  // dx/ds = -(b - a)/2 > 0 here: x falls from a as s falls from +1
    // Raw matrix times the chain-rule factor.
    const Eigen::VectorXd raw = jac * (grid.cumulative() * g);
    const Eigen::VectorXd helper = gaitopt::cumulativeOverInterval(grid, g, a, b);
    double err = 0.0;
    for (int k = 0; k < np; ++k) {
      const double exact = chebGAnti(x[k]) - chebGAnti(a);
      err = std::max(err, std::abs(raw[k] - exact));
      CHECK(std::abs(helper[k] - exact) < 1e-12);
    }
    reportMax("cumulative: mapped to [0.3, -0.2], n = 32", err);
    CHECK(err < 1e-12);
    const double total = gaitopt::integrateOverInterval(grid, g, a, b);
    CHECK(std::abs(total - (chebGAnti(b) - chebGAnti(a))) < 1e-14);
    CHECK(total < 0.0);  // g > 0 integrated from 0.3 down to -0.2
  }
}

TEST_CASE("chebyshev: interval map", "[chebyshev]") {
  const double a = 0.3, b = -0.2;
  CHECK(gaitopt::chebyshevToInterval(1.0, a, b) == a);
  CHECK(gaitopt::chebyshevToInterval(-1.0, a, b) == b);
  CHECK(gaitopt::chebyshevToInterval(0.0, a, b) == Approx(0.05));
  for (double s : {-0.9, -0.3, 0.0, 0.42, 1.0}) {
    const double x = gaitopt::chebyshevToInterval(s, a, b);
    CHECK(gaitopt::intervalToChebyshev(x, a, b) == Approx(s).margin(1e-15));
  }
  CHECK(gaitopt::intervalJacobian(a, b) == Approx(0.25));
  // Time map [0, T] with a plain 0 and an AD T.
  const AD2 T(2.0, Eigen::Vector2d(0.0, 1.0));
  const AD2 t = gaitopt::chebyshevToInterval(-0.5, 0, T);
  CHECK(t.value() == Approx(1.5));
  CHECK(t.derivatives()[1] == Approx(0.75));
  CHECK(gaitopt::valueOf(t) == t.value());
  using AD2N = Eigen::AutoDiffScalar<Eigen::Matrix<AD2, 2, 1>>;
  CHECK(gaitopt::valueOf(AD2N(AD2(1.25))) == 1.25);
  CHECK(gaitopt::cast<AD2>(3.0).derivatives().isZero());
}

TEST_CASE("chebyshev: interpolation and its derivative", "[chebyshev]") {
  const ChebyshevGrid grid(32);
  const int np = grid.size();
  const Eigen::VectorXd f = grid.nodes().array().exp().matrix();

  SECTION("random non-node points") {
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> uni(-1.0, 1.0);
    double err_p = 0.0, err_d = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const double s = uni(rng);
      err_p = std::max(err_p, std::abs(grid.interpolate(f, s) - std::exp(s)));
      err_d = std::max(err_d, std::abs(grid.interpolateDerivative(f, s) - std::exp(s)));
      const auto pd = grid.interpolateWithDerivative(f, s);
      CHECK(pd.first == grid.interpolate(f, s));
      CHECK(pd.second == grid.interpolateDerivative(f, s));
    }
    reportMax("interpolate exp(s), 2000 random s, n = 32", err_p);
    reportMax("interpolateDerivative exp(s), 2000 random s", err_d);
    CHECK(err_p < 1e-12);
    CHECK(err_d < 1e-12);
  }

  SECTION("exactly at nodes, and stable right next to them") {
    double err_d_node = 0.0, err_near = 0.0, err_near_d = 0.0;
    for (int k = 0; k < np; ++k) {
      const double sk = grid.nodes()[k];
      REQUIRE(grid.interpolate(f, sk) == f[k]);
      const double dk = grid.interpolateDerivative(f, sk);
      err_d_node = std::max(err_d_node, std::abs(dk - std::exp(sk)));
      CHECK(dk == Approx((grid.differentiation() * f)[k]).margin(1e-12));
      for (double off : {1e-15, -1e-15, 1e-12, -1e-9, 1e-6, -1e-4}) {
        const double s = sk + off;
        err_near = std::max(err_near, std::abs(grid.interpolate(f, s) - std::exp(s)));
        err_near_d = std::max(err_near_d, std::abs(grid.interpolateDerivative(f, s) - std::exp(s)));
      }
    }
    reportMax("interpolateDerivative exp(s) at the nodes", err_d_node);
    reportMax("interpolate exp(s) at s_k + 1e-15 .. 1e-4", err_near);
    reportMax("interpolateDerivative exp(s) at s_k + 1e-15 .. 1e-4", err_near_d);
    CHECK(err_d_node < 1e-12);
    CHECK(err_near < 1e-13);
    CHECK(err_near_d < 1e-12);
  }

  SECTION("std::vector values and small grids reproduce polynomials") {
    const ChebyshevGrid g(3);
    std::vector<double> v;
    for (int k = 0; k < g.size(); ++k) {
      const double s = g.nodes()[k];
      v.push_back(2.0 - s + 0.5 * s * s * s);
    }
    for (double s : {-0.77, 0.1, 0.999}) {
      CHECK(g.interpolate(v, s) == Approx(2.0 - s + 0.5 * s * s * s).margin(1e-14));
      CHECK(g.interpolateDerivative(v, s) == Approx(-1.0 + 1.5 * s * s).margin(1e-14));
    }
    REQUIRE_THROWS_AS(grid.interpolate(v, 0.2), std::invalid_argument);
  }

  SECTION("AD in s, including exactly at a node") {
    double err = 0.0;
    for (int k = 0; k < np; ++k) {
      for (double off : {0.0, 3e-3}) {
        const double s0 = grid.nodes()[k] + (k == 0 ? -off : off);  // stay inside [-1, 1]
        const AD2 s(s0, Eigen::Vector2d(1.0, 0.0));
        const AD2 p = grid.interpolate(f, s);
        const AD2 dp = grid.interpolateDerivative(f, s);
        if (off == 0.0) CHECK(p.value() == f[k]);
        err = std::max(err, std::abs(p.derivatives()[0] - std::exp(s0)));
        err = std::max(err, std::abs(dp.derivatives()[0] - std::exp(s0)));  // second derivative
        CHECK(p.derivatives()[1] == 0.0);
      }
    }
    reportMax("AD d/ds of p and p' (exp), at and near nodes", err);
    CHECK(err < 1e-10);
  }
}

TEST_CASE("chebyshev: AD through parameter-dependent end points", "[chebyshev]") {
  const ChebyshevGrid grid(32);
  const int np = grid.size();
  const double a0 = 0.3, b0 = -0.2;
  const AD2 a(a0, Eigen::Vector2d(1.0, 0.0));
  const AD2 b(b0, Eigen::Vector2d(0.0, 1.0));

  // Everything through the grid: nodes follow (a, b), integrand sampled on them.
  auto integral = [&](const auto& aa, const auto& bb) {
    using T = std::decay_t<decltype(aa)>;
    Eigen::Matrix<T, Eigen::Dynamic, 1> g(np);
    for (int k = 0; k < np; ++k) g[k] = chebG(gaitopt::chebyshevToInterval(grid.nodes()[k], aa, bb));
    return gaitopt::integrateOverInterval(grid, g, aa, bb);
  };

  SECTION("integral over [a, b]: AD vs analytic and finite differences") {
  const AD2 I = integral(a, b);
  CHECK(std::abs(I.value() - (chebGAnti(b0) - chebGAnti(a0))) < 1e-14);
  // d/da ∫_a^b g = -g(a), d/db = g(b).
  const double err_a = std::abs(I.derivatives()[0] - (-chebG(a0)));
  const double err_b = std::abs(I.derivatives()[1] - chebG(b0));
  reportMax("AD dI/da vs analytic -g(a)", err_a);
  reportMax("AD dI/db vs analytic  g(b)", err_b);
  CHECK(err_a < 1e-10);
  CHECK(err_b < 1e-10);

  // Central finite differences on the double path.
  const double h = 1e-6;
  const double fd_a = (integral(a0 + h, b0) - integral(a0 - h, b0)) / (2 * h);
  const double fd_b = (integral(a0, b0 + h) - integral(a0, b0 - h)) / (2 * h);
  const double err_fd = std::max(std::abs(fd_a - I.derivatives()[0]), std::abs(fd_b - I.derivatives()[1]));
  reportMax("AD vs central FD (h = 1e-6)", err_fd);
  CHECK(err_fd < 1e-8);
  }

  SECTION("cumulative: node k follows (a, b)") {
    Eigen::Matrix<AD2, Eigen::Dynamic, 1> g(np);
    const auto x = gaitopt::mappedNodes(grid, a, b);
    for (int k = 0; k < np; ++k) g[k] = chebG(x[k]);
    const auto F = gaitopt::cumulativeOverInterval(grid, g, a, b);
    double err = 0.0;
    for (int k = 0; k < np; ++k) {
      // F_k = G(x_k(a, b)) - G(a), x_k = a + (1 - s_k)/2 (b - a).
      const double xk = x[k].value(), t = 0.5 * (1.0 - grid.nodes()[k]);
      err = std::max(err, std::abs(F[k].derivatives()[0] - (chebG(xk) * (1.0 - t) - chebG(a0))));
      err = std::max(err, std::abs(F[k].derivatives()[1] - chebG(xk) * t));
    }
    reportMax("AD of cumulative integrals vs analytic", err);
    CHECK(err < 1e-10);
  }

  SECTION("interpolating at a fixed physical point is independent of (a, b)") {
    Eigen::Matrix<AD2, Eigen::Dynamic, 1> g(np);
    const auto x = gaitopt::mappedNodes(grid, a, b);
    for (int k = 0; k < np; ++k) g[k] = chebG(x[k]);
    for (double x0 : {0.25, 0.0, -0.13}) {
      const AD2 s = gaitopt::intervalToChebyshev(x0, a, b);  // AD s and AD values
      const AD2 p = grid.interpolate(g, s);
      CHECK(std::abs(p.value() - chebG(x0)) < 1e-13);
      CHECK(p.derivatives().cwiseAbs().maxCoeff() < 1e-11);
      // d/dx of g at x0 through the chain rule ds/dx = 1 / (dx/ds).
      const AD2 dpds = grid.interpolateDerivative(g, s);
      const AD2 dgdx = dpds / gaitopt::intervalJacobian(a, b);
      CHECK(std::abs(dgdx.value() - (-3.0 * std::sin(3.0 * x0) + 2.0 * x0)) < 1e-11);
      CHECK(dgdx.derivatives().cwiseAbs().maxCoeff() < 1e-9);
    }
  }
}

TEST_CASE("chebyshev: grids of one degree share their tables, rebuilt alike once evicted",
          "[chebyshev]") {
  const ChebyshevGrid a(48), b(48);
  CHECK(&a.cumulative() == &b.cumulative());  // built once (O(n^3)), not per grid
  const Eigen::MatrixXd cumulative = a.cumulative();
  const Eigen::MatrixXd differentiation = a.differentiation();
  // More degrees than the shared store keeps: 48 is evicted, a new grid rebuilds its tables.
  for (int n = 2; n < 20; ++n) CHECK(ChebyshevGrid(n).degree() == n);
  const ChebyshevGrid c(48);
  CHECK(c.cumulative() == cumulative);  // bit-identical: the same computation
  CHECK(c.differentiation() == differentiation);
  CHECK(a.cumulative() == cumulative);  // the old grid still holds its own tables
}
