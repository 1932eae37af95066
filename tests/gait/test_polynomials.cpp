// The virtual-constraint polynomials meet their interpolation conditions for any number of
// interior points, and the one-point case is the thesis' quartic (3.25).
#include <catch2/catch.hpp>
#include <cmath>

#include "gaitopt/gait/polynomials.hpp"

using namespace gaitopt;

TEST_CASE("polynomials through end values, end slopes and K interior values", "[polynomials]") {
  const double x0 = 0.3, x1 = -0.4, y0 = -2.7, y1 = -2.2, m0 = 0.8, m1 = -1.3;
  for (int K = 0; K <= 4; ++K) {
    std::vector<double> xs, ys;
    for (int k = 1; k <= K; ++k) {
      xs.push_back(x0 + (x1 - x0) * k / (K + 1.0));
      ys.push_back(-2.5 + 0.1 * std::sin(3.0 * k));
    }
    const LocalPolynomial<double> p = polynomialThrough(x0, y0, m0, xs, ys, x1, y1, m1);
    INFO("K = " << K);
    CHECK(p.c.size() == static_cast<std::size_t>(4 + K));
    CHECK(p(x0).value == Approx(y0).margin(1e-13));
    CHECK(p(x1).value == Approx(y1).margin(1e-12));
    CHECK(p(x0).first == Approx(m0).margin(1e-12));
    CHECK(p(x1).first == Approx(m1).margin(1e-10));
    for (int k = 0; k < K; ++k) CHECK(p(xs[k]).value == Approx(ys[k]).margin(1e-12));
  }
}

TEST_CASE("polynomial derivatives equal finite differences", "[polynomials]") {
  const LocalPolynomial<double> p =
      polynomialThrough(0.2, 1.0, -0.5, std::vector<double>{0.0, -0.1}, std::vector<double>{1.3, 0.9},
                        -0.3, 0.7, 2.0);
  const double h = 1e-6;
  for (double x : {0.15, 0.0, -0.05, -0.25}) {
    CHECK(p(x).first == Approx((p(x + h).value - p(x - h).value) / (2 * h)).epsilon(1e-8));
    CHECK(p(x).second == Approx((p(x + h).first - p(x - h).first) / (2 * h)).epsilon(1e-7));
  }
}

TEST_CASE("one interior point gives the quartic of (3.25)", "[polynomials]") {
  // Solve the 5×5 system of (3.25) directly and compare coefficients (in x, not x − x0).
  const double a0 = 0.1, ai = -0.1, af = -0.3, d0 = -2.8, di = -2.6, df = -2.4, s0 = 0.4, sf = -0.2;
  const LocalPolynomial<double> p = polynomialThrough(a0, d0, s0, std::vector<double>{ai},
                                                      std::vector<double>{di}, af, df, sf);
  // Conditions written against the monomial basis of x.
  double A[5][5], b[5] = {d0, s0, di, df, sf};
  const double xs[5] = {a0, a0, ai, af, af};
  const bool slope[5] = {false, true, false, false, true};
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 5; ++c)
      A[r][c] = slope[r] ? (c == 0 ? 0.0 : c * std::pow(xs[r], c - 1)) : std::pow(xs[r], c);
  for (int i = 0; i < 5; ++i)  // Gaussian elimination (distinct nodes: no zero pivot here)
    for (int r = i + 1; r < 5; ++r) {
      const double f = A[r][i] / A[i][i];
      for (int c = i; c < 5; ++c) A[r][c] -= f * A[i][c];
      b[r] -= f * b[i];
    }
  double coef[5];
  for (int i = 4; i >= 0; --i) {
    double s = b[i];
    for (int c = i + 1; c < 5; ++c) s -= A[i][c] * coef[c];
    coef[i] = s / A[i][i];
  }
  for (double x : {0.05, -0.2, -0.28}) {
    double direct = 0.0;
    for (int k = 4; k >= 0; --k) direct = direct * x + coef[k];
    CHECK(p(x).value == Approx(direct).epsilon(1e-11));
  }
}
