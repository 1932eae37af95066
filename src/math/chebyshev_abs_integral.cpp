// Root location and integration weights of math/chebyshev_abs_integral.hpp (double only).
#include "gaitopt/math/chebyshev_abs_integral.hpp"

#include <algorithm>
#include <cmath>

#include "gaitopt/math/bracketed_root.hpp"

namespace gaitopt {

namespace {

// p(x) = Σ_j a_j T_j(x) and p′(x) by Clenshaw's recurrence b_j = a_j + 2x b_{j+1} − b_{j+2}
// and its derivative in x; O(n), no division (the barycentric formula divides per node).
std::pair<double, double> seriesWithDerivative(const Eigen::VectorXd& a, double x) {
  double b1 = 0.0, b2 = 0.0, d1 = 0.0, d2 = 0.0;
  for (Eigen::Index j = a.size() - 1; j >= 1; --j) {
    const double b0 = a[j] + 2.0 * x * b1 - b2;
    const double d0 = 2.0 * b1 + 2.0 * x * d1 - d2;
    b2 = b1;
    b1 = b0;
    d2 = d1;
    d1 = d0;
  }
  return {a[0] + x * b1 - b2, b1 + x * d1 - d2};
}

// The sign change of the series in [lo, hi] (p(lo), p(hi) of opposite signs): Newton, kept in
// the bracket (a regula falsi step on the bracket when a Newton step leaves it, e.g. when an
// end is itself the root). Quadratic near a simple root, so after a step below 1e-8 the root
// is exact to rounding (a tighter test would chase rounding noise in p).
InterpolantSignChange seriesRoot(const Eigen::VectorXd& a, double lo, double f_lo, double hi,
                                 double f_hi) {
  const auto falsi = [&] {
    const double x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    return x >= lo && x <= hi ? x : 0.5 * (lo + hi);
  };
  double x = falsi(), slope = 0.0;
  for (int it = 0; it < 60; ++it) {
    const auto [p, dp] = seriesWithDerivative(a, x);
    slope = dp;
    if (p == 0.0) break;
    if ((p < 0.0) == (f_lo < 0.0)) {
      lo = x;
      f_lo = p;
    } else {
      hi = x;
      f_hi = p;
    }
    double next = x - p / dp;
    if (!(next >= lo && next <= hi)) next = falsi();
    const double step = std::abs(next - x);
    x = next;
    if (step <= 1e-8 || hi - lo <= 1e-15) break;
  }
  return {x, slope};
}

}  // namespace

std::vector<InterpolantSignChange> interpolantSignChanges(const ChebyshevGrid& grid,
                                                          const Eigen::VectorXd& values) {
  const Eigen::VectorXd& s = grid.nodes();
  const int last = grid.size() - 1;
  // The series' coefficients (an O(n²) product) only once a sign change or a candidate extremum
  // needs them: most phases' integrands have a few roots or none.
  Eigen::VectorXd a;
  const auto coefficients = [&]() -> const Eigen::VectorXd& {
    if (a.size() == 0) a = grid.coefficients() * values;
    return a;
  };
  // |f| has a discrete local minimum at node k, between neighbours of the same sign.
  const auto level = [&values](int k, double v) {
    return (values[k] < 0.0) == (v < 0.0) && std::abs(v) <= std::abs(values[k]);
  };
  const auto dips = [&values, &level, last](int k) {
    return (k == 0 || level(k - 1, values[k])) && (k == last || level(k + 1, values[k]));
  };
  std::vector<InterpolantSignChange> roots;
  for (int k = 0; k < last; ++k) {
    // Node k is the upper end of the interval: the brackets run from s_{k+1} up to s_k.
    const double lo = s[k + 1], hi = s[k], f_lo = values[k + 1], f_hi = values[k];
    if ((f_lo < 0.0) != (f_hi < 0.0)) {
      roots.push_back(seriesRoot(coefficients(), lo, f_lo, hi, f_hi));
      continue;
    }
    // A pair of roots between nodes of equal sign lies around an extremum of p towards zero,
    // next to a node where |f| dips, where p′ changes sign and whose values are within reach of
    // the slopes over the interval; the tests skip the search for the other intervals.
    if (!dips(k) && !dips(k + 1)) continue;
    // The slopes' reach below, first estimated by the nodal differences around the interval
    // (with a margin of 2) so that most dips cost no series evaluation.
    double variation = std::abs(f_hi - f_lo);
    if (k > 0) variation = std::max(variation, std::abs(values[k - 1] - f_hi));
    if (k + 1 < last) variation = std::max(variation, std::abs(values[k + 2] - f_lo));
    if (std::min(std::abs(f_lo), std::abs(f_hi)) > 2.0 * variation) continue;
    const double slope_lo = seriesWithDerivative(coefficients(), lo).second;
    const double slope_hi = seriesWithDerivative(a, hi).second;
    if ((slope_lo < 0.0) == (slope_hi < 0.0) ||
        std::min(std::abs(f_lo), std::abs(f_hi)) >
            (hi - lo) * std::max(std::abs(slope_lo), std::abs(slope_hi)))
      continue;
    const auto dp = [&a](double x) { return seriesWithDerivative(a, x).second; };
    const double e = bracketedRoot(dp, lo, slope_lo, hi, slope_hi);
    const double f_e = seriesWithDerivative(a, e).first;
    if ((f_e < 0.0) == (f_lo < 0.0)) continue;
    roots.push_back(seriesRoot(a, e, f_e, hi, f_hi));
    roots.push_back(seriesRoot(a, lo, f_lo, e, f_e));
  }
  return roots;
}

Eigen::VectorXd absIntegralWeights(const ChebyshevGrid& grid, const Eigen::VectorXd& values,
                                   const std::vector<InterpolantSignChange>& roots) {
  // With F(s) = ∫_{+1}^{s} p = cumulativeAt(s)·f, ∫|p| = Σ_k σ_k (F(e_k) − F(e_{k+1})) over the
  // pieces between consecutive ends e (+1, the roots, −1), σ_k the piece's sign: that of p(+1)
  // in the first piece, alternating since every root is a sign change. F(+1) = 0 and
  // F(−1) = −w·f, so u = Σ_roots 2σ_k cumulativeAt(e_k) + σ_last w, σ_k the sign of the piece
  // just below root e_k (the plain weights, bit for bit, when there is no root).
  double sign = values[0] < 0.0 ? -1.0 : 1.0;
  std::vector<double> points, factors;
  for (const InterpolantSignChange& root : roots) {
    sign = -sign;
    points.push_back(root.s);
    factors.push_back(2.0 * sign);
  }
  Eigen::VectorXd u = sign * grid.weights();
  if (!roots.empty()) u += grid.cumulativeCombination(points, factors).transpose();
  return u;
}

}  // namespace gaitopt
