#include "gaitopt/math/smoothing_spline.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace gaitopt {

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

// Q (n × n−2, second divided differences) and R (n−2 × n−2, tridiagonal) of Green & Silverman
// (2.3): ∫ g''² = γᵀ R γ and Qᵀ g = R γ for the natural cubic spline through g.
void reinschMatrices(const Eigen::VectorXd& t, Eigen::SparseMatrix<double>& Q,
                     Eigen::SparseMatrix<double>& R) {
  const Eigen::Index n = t.size();
  Triplets q, r;
  for (Eigen::Index j = 1; j + 1 < n; ++j) {
    const double h0 = t(j) - t(j - 1), h1 = t(j + 1) - t(j);
    q.emplace_back(j - 1, j - 1, 1.0 / h0);
    q.emplace_back(j, j - 1, -1.0 / h0 - 1.0 / h1);
    q.emplace_back(j + 1, j - 1, 1.0 / h1);
    r.emplace_back(j - 1, j - 1, (h0 + h1) / 3.0);
    if (j + 2 < n) {
      r.emplace_back(j - 1, j, h1 / 6.0);
      r.emplace_back(j, j - 1, h1 / 6.0);
    }
  }
  Q.resize(n, n - 2);
  Q.setFromTriplets(q.begin(), q.end());
  R.resize(n - 2, n - 2);
  R.setFromTriplets(r.begin(), r.end());
}

}  // namespace

SmoothingSpline::SmoothingSpline(const Eigen::VectorXd& t, const Eigen::MatrixXd& y,
                                 double lambda)
    : t_(t) {
  const Eigen::Index n = t.size();
  if (n < 3 || y.rows() != n) throw std::invalid_argument("smoothing spline: need n >= 3 samples");
  if (!(lambda >= 0.0)) throw std::invalid_argument("smoothing spline: lambda must be >= 0");
  for (Eigen::Index i = 1; i < n; ++i)
    if (!(t(i) > t(i - 1))) throw std::invalid_argument("smoothing spline: times must increase");
  Eigen::SparseMatrix<double> Q, R;
  reinschMatrices(t, Q, R);
  // Reinsch: (R + λ QᵀQ) γ = Qᵀ y, then g = y − λ Q γ (pentadiagonal SPD system).
  const Eigen::SparseMatrix<double> system = R + lambda * Eigen::SparseMatrix<double>(Q.transpose() * Q);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(system);
  if (ldlt.info() != Eigen::Success) throw std::runtime_error("smoothing spline: factorisation failed");
  const Eigen::MatrixXd interior = ldlt.solve(Eigen::MatrixXd(Q.transpose() * y));
  g_ = y - lambda * (Q * interior);
  gamma_ = Eigen::MatrixXd::Zero(n, y.cols());
  gamma_.middleRows(1, n - 2) = interior;
}

Eigen::RowVectorXd SmoothingSpline::evaluate(double s, int order) const {
  const Eigen::Index n = t_.size();
  const Eigen::Index i = std::clamp<Eigen::Index>(
      std::upper_bound(t_.data(), t_.data() + n, s) - t_.data() - 1, 0, n - 2);
  const double h = t_(i + 1) - t_(i), x = s - t_(i);
  const Eigen::RowVectorXd g0 = g_.row(i), g1 = g_.row(i + 1);
  const Eigen::RowVectorXd c0 = gamma_.row(i), c1 = gamma_.row(i + 1);
  // Piece i as g0 + b x + (c0/2) x² + d x³ (natural spline from values and second derivatives).
  const Eigen::RowVectorXd b = (g1 - g0) / h - h * (2.0 * c0 + c1) / 6.0;
  const Eigen::RowVectorXd d = (c1 - c0) / (6.0 * h);
  if (s > t_(n - 1) || s < t_(0)) {  // linear extension beyond the natural ends
    const bool after = s > t_(n - 1);
    const double e = after ? s - t_(n - 1) : s - t_(0);
    const Eigen::RowVectorXd slope = after ? Eigen::RowVectorXd(b + c0 * h + 3.0 * d * h * h) : b;
    const Eigen::RowVectorXd end = after ? g1 : g0;
    if (order == 0) return end + slope * e;
    if (order == 1) return slope;
    return Eigen::RowVectorXd::Zero(g_.cols());
  }
  if (order == 0) return g0 + x * (b + x * (0.5 * c0 + x * d));
  if (order == 1) return b + x * (c0 + 3.0 * x * d);
  if (order == 2) return c0 + 6.0 * x * d;
  throw std::invalid_argument("smoothing spline: order must be 0, 1 or 2");
}

Eigen::MatrixXd SmoothingSpline::evaluate(const Eigen::VectorXd& s, int order) const {
  Eigen::MatrixXd out(s.size(), g_.cols());
  for (Eigen::Index k = 0; k < s.size(); ++k) out.row(k) = evaluate(s(k), order);
  return out;
}

double smoothingLambdaForCutoff(double dt, double cutoff_hz) {
  const double omega = 2.0 * M_PI * cutoff_hz;
  return 1.0 / (dt * std::pow(omega, 4));
}

}  // namespace gaitopt
