#include "gaitopt/math/fmm_spline.hpp"

#include <algorithm>

namespace gaitopt {
namespace {

// σ_i = S''(x_i)/6 of the spline: the tridiagonal system of C² continuity at the inner knots
// h_{i-1} σ_{i-1} + 2 (h_{i-1} + h_i) σ_i + h_i σ_{i+1} = δ_i − δ_{i-1}, closed by the
// third-derivative end conditions, solved by elimination (diagonally dominant inside).
std::vector<double> splineSigma(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  std::vector<double> h(n - 1), delta(n - 1), diag(n), rhs(n, 0.0);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = x[i + 1] - x[i];
    delta[i] = (y[i + 1] - y[i]) / h[i];
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    diag[i] = 2.0 * (h[i - 1] + h[i]);
    rhs[i] = delta[i] - delta[i - 1];
  }
  // End rows −h σ_0 + h σ_1 = h² Δ³ (and mirrored): Δ³ the third divided difference of the
  // four end knots; with three knots the right side is 0 (constant S'' near the ends).
  diag[0] = -h[0];
  diag[n - 1] = -h[n - 2];
  if (n > 3) {
    const double first = rhs[2] / (x[3] - x[1]) - rhs[1] / (x[2] - x[0]);
    const double last = rhs[n - 2] / (x[n - 1] - x[n - 3]) - rhs[n - 3] / (x[n - 2] - x[n - 4]);
    rhs[0] = first * h[0] * h[0] / (x[3] - x[0]);
    rhs[n - 1] = -last * h[n - 2] * h[n - 2] / (x[n - 1] - x[n - 4]);
  }
  for (std::size_t i = 1; i < n; ++i) {  // forward elimination; off-diagonals are h
    const double factor = h[i - 1] / diag[i - 1];
    diag[i] -= factor * h[i - 1];
    rhs[i] -= factor * rhs[i - 1];
  }
  std::vector<double> sigma(n);
  sigma[n - 1] = rhs[n - 1] / diag[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) sigma[i] = (rhs[i] - h[i] * sigma[i + 1]) / diag[i];
  return sigma;
}

}  // namespace

double fmmSplineValue(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  const std::size_t n = xs.size();
  if (n == 2) return ys[0] + (x - xs[0]) * (ys[1] - ys[0]) / (xs[1] - xs[0]);
  const std::vector<double> sigma = splineSigma(xs, ys);
  // Slope of piece k at its left knot: δ_k − h_k (σ_{k+1} + 2 σ_k).
  const auto slope = [&](std::size_t k) {
    const double h = xs[k + 1] - xs[k];
    return (ys[k + 1] - ys[k]) / h - h * (sigma[k + 1] + 2.0 * sigma[k]);
  };
  if (x <= xs[0]) return ys[0] + (x - xs[0]) * slope(0);
  if (x >= xs[n - 1]) {
    const double h = xs[n - 1] - xs[n - 2];
    const double end_slope = (ys[n - 1] - ys[n - 2]) / h + h * (sigma[n - 2] + 2.0 * sigma[n - 1]);
    return ys[n - 1] + (x - xs[n - 1]) * end_slope;
  }
  const std::size_t k =
      static_cast<std::size_t>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin()) - 1;
  const double dx = x - xs[k];
  const double h = xs[k + 1] - xs[k];
  const double cubic = (sigma[k + 1] - sigma[k]) / h;
  return ys[k] + dx * (slope(k) + dx * (3.0 * sigma[k] + dx * cubic));
}

}  // namespace gaitopt
