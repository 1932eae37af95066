#include "gaitopt/math/nonnegative_least_squares.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <vector>

namespace gaitopt {
namespace {

// Least squares on the columns in `passive` (the others zero).
Eigen::VectorXd passiveSolution(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                const std::vector<bool>& passive) {
  std::vector<int> cols;
  for (int j = 0; j < A.cols(); ++j)
    if (passive[j]) cols.push_back(j);
  Eigen::MatrixXd Ap(A.rows(), cols.size());
  for (std::size_t k = 0; k < cols.size(); ++k) Ap.col(k) = A.col(cols[k]);
  const Eigen::VectorXd zp = Ap.completeOrthogonalDecomposition().solve(b);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(A.cols());
  for (std::size_t k = 0; k < cols.size(); ++k) z(cols[k]) = zp(k);
  return z;
}

}  // namespace

NnlsResult solveNonnegativeLeastSquares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const int n = static_cast<int>(A.cols());
  // Gradient entries below this (relative to ‖Aᵀb‖) count as zero: the KKT test.
  const double tol = 1e-12 * std::max(1.0, (A.transpose() * b).cwiseAbs().maxCoeff());
  NnlsResult r;
  r.x = Eigen::VectorXd::Zero(n);
  std::vector<bool> passive(n, false);
  for (int outer = 0; outer < 3 * n; ++outer) {
    const Eigen::VectorXd w = A.transpose() * (b - A * r.x);
    int j = -1;
    for (int k = 0; k < n; ++k)
      if (!passive[k] && w(k) > tol && (j < 0 || w(k) > w(j))) j = k;
    if (j < 0) {
      r.converged = true;
      break;
    }
    passive[j] = true;
    for (int inner = 0; inner < 3 * n; ++inner) {
      const Eigen::VectorXd z = passiveSolution(A, b, passive);
      // Step from x towards z as far as every passive entry stays ≥ 0.
      double alpha = 1.0;
      for (int k = 0; k < n; ++k)
        if (passive[k] && z(k) <= 0.0) alpha = std::min(alpha, r.x(k) / (r.x(k) - z(k)));
      r.x += alpha * (z - r.x);
      if (alpha >= 1.0) break;
      for (int k = 0; k < n; ++k)
        if (passive[k] && r.x(k) <= tol) {
          passive[k] = false;
          r.x(k) = 0.0;
        }
    }
  }
  r.residual = (A * r.x - b).norm();
  return r;
}

}  // namespace gaitopt
