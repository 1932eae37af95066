// Double-only precomputation for ChebyshevGrid (see include/gaitopt/math/chebyshev.hpp).
#include "gaitopt/math/chebyshev.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "gaitopt/math/degree_cache.hpp"

namespace gaitopt {

namespace {

constexpr double kPi = 3.14159265358979323846;

// cos(pi m / n) for an integer m, reduced exactly in integers and evaluated as a sine about
// the zero crossing, so symmetric nodes are exact negatives and the middle node is exactly 0.
double cosPiRatio(long long m, int n) {
  const long long two_n = 2LL * n;
  long long r = m % two_n;
  if (r < 0) r += two_n;
  if (r > n) r = two_n - r;  // cos is even about pi
  return std::sin(kPi * static_cast<double>(n - 2 * r) / (2.0 * n));
}

// sin(pi m / (2n)) for an integer m, used for cancellation-free node differences.
double sinPiHalfRatio(long long m, int n) { return std::sin(kPi * static_cast<double>(m) / (2.0 * n)); }

}  // namespace

ChebyshevGrid::ChebyshevGrid(int n) : n_(n), t_(sharedTables(n)) {}

std::shared_ptr<const ChebyshevGrid::Tables> ChebyshevGrid::sharedTables(int n) {
  if (n < 2) throw std::invalid_argument("ChebyshevGrid: need n >= 2");
  return sharedByDegree<Tables>(n, computeTables);
}

ChebyshevGrid::Tables ChebyshevGrid::computeTables(int n) {
  Tables t;
  const int np = n + 1;

  // Nodes s_k = cos(pi k / n).
  t.nodes.resize(np);
  for (int k = 0; k <= n; ++k) t.nodes[k] = cosPiRatio(k, n);

  // Barycentric weights for Chebyshev–Lobatto points: (-1)^k, halved at the end points.
  t.barycentric.resize(np);
  for (int k = 0; k <= n; ++k) t.barycentric[k] = ((k % 2 == 0) ? 1.0 : -1.0) * ((k == 0 || k == n) ? 0.5 : 1.0);

  // Clenshaw–Curtis weights (closed-form cosine sums).
  t.weights.setZero(np);
  {
    Eigen::VectorXd v = Eigen::VectorXd::Ones(np);
    if (n % 2 == 0) {
      t.weights[0] = t.weights[n] = 1.0 / (static_cast<double>(n) * n - 1.0);
      for (int k = 1; k < n / 2; ++k)
        for (int i = 1; i < n; ++i) v[i] -= 2.0 * cosPiRatio(2LL * k * i, n) / (4.0 * k * k - 1.0);
      for (int i = 1; i < n; ++i) v[i] -= cosPiRatio(static_cast<long long>(n) * i, n) / (static_cast<double>(n) * n - 1.0);
    } else {
      t.weights[0] = t.weights[n] = 1.0 / (static_cast<double>(n) * n);
      for (int k = 1; k <= (n - 1) / 2; ++k)
        for (int i = 1; i < n; ++i) v[i] -= 2.0 * cosPiRatio(2LL * k * i, n) / (4.0 * k * k - 1.0);
    }
    for (int i = 1; i < n; ++i) t.weights[i] = 2.0 * v[i] / n;
  }

  // Values -> Chebyshev coefficients (DCT-I as a matrix): f = Σ_j a_j T_j,
  // a_j = 2 / (n c_j) Σ_k f_k cos(pi j k / n) / c_k, c_0 = c_n = 2, else 1.
  auto endFactor = [n](int i) { return (i == 0 || i == n) ? 2.0 : 1.0; };
  Eigen::MatrixXd to_coeffs(np, np);
  for (int j = 0; j <= n; ++j)
    for (int k = 0; k <= n; ++k)
      to_coeffs(j, k) = 2.0 / (n * endFactor(j) * endFactor(k)) * cosPiRatio(static_cast<long long>(j) * k, n);

  // Integrate the series term by term (constant of integration fixed below):
  // ∫T_0 = T_1, ∫T_1 = T_2/4, ∫T_j = (T_{j+1}/(j+1) - T_{j-1}/(j-1))/2 for j >= 2: an
  // (n+2) × (n+1) matrix with at most two entries per row and per column, (row, column, value).
  std::vector<std::tuple<int, int, double>> integrate{{1, 0, 1.0}, {2, 1, 0.25}};
  for (int j = 2; j <= n; ++j) {
    integrate.emplace_back(j + 1, j, 0.5 / (j + 1));
    integrate.emplace_back(j - 1, j, -(0.5 / (j - 1)));
  }

  // Evaluate the degree n+1 antiderivative at the nodes (T_m(s_k) = cos(pi m k / n)) minus its
  // value at s = +1 (T_m(1) = 1), so each row is ∫_{+1}^{s_k}.
  Eigen::MatrixXd evaluate_minus_top(np, n + 2);
  for (int k = 0; k <= n; ++k)
    for (int m = 0; m <= n + 1; ++m)
      evaluate_minus_top(k, m) = cosPiRatio(static_cast<long long>(m) * k, n) - 1.0;
  // The products with the integration matrix from its entries, O(n²): each entry is the sum of
  // the two products a dense product adds to zero, its other terms being exact zeros, so the
  // numbers are the dense products' (the O(n³) products made a 10× finer grid cost 40 ms).
  t.antiderivative.setZero(n + 2, np);
  Eigen::MatrixXd evaluated_integral = Eigen::MatrixXd::Zero(np, np);
  for (const auto& [row, col, v] : integrate) {
    t.antiderivative.row(row) += v * to_coeffs.row(col);
    evaluated_integral.col(col) += v * evaluate_minus_top.col(row);
  }
  t.coefficients = to_coeffs;
  t.cumulative = evaluated_integral * to_coeffs;  // this order: bit-stable results
  t.cumulative.row(0).setZero();  // already zero in exact arithmetic; make it bit-exact

  // Differentiation matrix D_jk = (w_k / w_j) / (s_j - s_k) with the barycentric weights; node
  // differences via s_j - s_k = -2 sin(pi (j+k) / 2n) sin(pi (j-k) / 2n); diagonal by the
  // negative-sum trick so constants differentiate to exactly 0.
  t.differentiation.setZero(np, np);
  for (int j = 0; j <= n; ++j) {
    double row_sum = 0.0;
    for (int k = 0; k <= n; ++k) {
      if (k == j) continue;
      const double diff = -2.0 * sinPiHalfRatio(j + k, n) * sinPiHalfRatio(j - k, n);
      const double d = (t.barycentric[k] / t.barycentric[j]) / diff;
      t.differentiation(j, k) = d;
      row_sum += d;
    }
    t.differentiation(j, j) = -row_sum;
  }
  return t;
}

Eigen::RowVectorXd ChebyshevGrid::cumulativeAt(double s) const {
  return cumulativeCombination({s}, {1.0});
}

Eigen::RowVectorXd ChebyshevGrid::cumulativeCombination(const std::vector<double>& points,
                                                        const std::vector<double>& factors) const {
  // Σ_i c_i (T_m(s_i) − T_m(1)) by the three-term recurrence, then through the antiderivative's
  // coefficients once (as the rows of cumulative() at the nodes).
  Eigen::RowVectorXd t = Eigen::RowVectorXd::Zero(n_ + 2);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double s = points[i], c = factors[i];
    double t_prev = 1.0, t_cur = s;
    t[1] += c * (s - 1.0);
    for (int m = 2; m <= n_ + 1; ++m) {
      const double t_next = 2.0 * s * t_cur - t_prev;
      t[m] += c * (t_next - 1.0);
      t_prev = t_cur;
      t_cur = t_next;
    }
  }
  return t * t_->antiderivative;
}

int ChebyshevGrid::nearestNode(double s) const {
  if (!(s == s)) return 0;  // NaN: any index; the result is NaN anyway
  if (s >= 1.0) return 0;
  if (s <= -1.0) return n_;
  const double t = std::acos(s) * n_ / kPi;
  int j0 = static_cast<int>(std::lround(t));
  j0 = std::clamp(j0, 0, n_);
  int best = j0;
  double best_dist = std::abs(s - t_->nodes[j0]);
  for (int j = std::max(0, j0 - 1); j <= std::min(n_, j0 + 1); ++j) {
    const double dist = std::abs(s - t_->nodes[j]);
    if (dist < best_dist) {
      best = j;
      best_dist = dist;
    }
  }
  return best;
}

}  // namespace gaitopt
