#include "gaitopt/math/small_qp.hpp"

#include <Eigen/Dense>
#include <vector>

namespace gaitopt {
namespace {

// Whether z = −Gsᵀλ with Gs z = hs (the rows of `rows` active) is a KKT point of
// min ½‖z‖² s.t. Gz z ≤ hz.
bool kktPoint(const Eigen::MatrixXd& Gz, const Eigen::VectorXd& hz, const std::vector<int>& rows,
              double tol, Eigen::VectorXd& z) {
  const Eigen::Index k = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd Gs(k, Gz.cols());
  Eigen::VectorXd hs(k);
  for (Eigen::Index i = 0; i < k; ++i) {
    Gs.row(i) = Gz.row(rows[i]);
    hs(i) = hz(rows[i]);
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(Gs * Gs.transpose());
  if (lu.rank() < k) return false;  // dependent rows: a smaller set carries the same optimum
  const Eigen::VectorXd lambda = -lu.solve(hs);
  if (lambda.minCoeff() < -tol * (1.0 + lambda.cwiseAbs().maxCoeff())) return false;
  z = -Gs.transpose() * lambda;
  const Eigen::VectorXd slack = hz - Gz * z;
  for (Eigen::Index i = 0; i < Gz.rows(); ++i)
    if (slack(i) < -tol * (Gz.row(i).norm() * z.norm() + std::abs(hz(i)) + 1.0)) return false;
  return true;
}

}  // namespace

SmallQpResult solveLeastDistanceQp(const Eigen::MatrixXd& G, const Eigen::VectorXd& h,
                                   const Eigen::VectorXd& w, const Eigen::VectorXd& x0,
                                   double tolerance) {
  // z = √w ∘ (x − x0): min ½‖z‖² s.t. G diag(1/√w) z ≤ h − G x0.
  const Eigen::VectorXd s = w.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd Gz = G * s.asDiagonal();
  const Eigen::VectorXd hz = h - G * x0;
  SmallQpResult r;
  r.x = x0;
  if (hz.minCoeff() >= 0.0) {
    r.feasible = true;
    return r;
  }
  const int m = static_cast<int>(G.rows());
  const int n = static_cast<int>(G.cols());
  Eigen::VectorXd z;
  std::vector<int> rows;
  for (int size = 1; size <= n && size <= m; ++size)
    for (unsigned mask = 1; mask < (1u << m); ++mask) {
      if (__builtin_popcount(mask) != size) continue;
      rows.clear();
      for (int i = 0; i < m; ++i)
        if (mask & (1u << i)) rows.push_back(i);
      if (!kktPoint(Gz, hz, rows, tolerance, z)) continue;
      r.feasible = true;
      r.active = size;
      r.x = x0 + s.cwiseProduct(z);
      return r;
    }
  return r;
}

}  // namespace gaitopt
