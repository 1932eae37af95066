#include "gaitopt/opt/hessian_modification.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>

namespace gaitopt {

MatrixX positiveOnNullSpace(const MatrixX& hess, const MatrixX& active, double min_eigenvalue) {
  const int n = static_cast<int>(hess.rows());
  MatrixX z = MatrixX::Identity(n, n);
  if (active.rows() > 0) {
    // Columns rank..n−1 of the Q of Aᵀ = Q R span the null space of A.
    const Eigen::ColPivHouseholderQR<MatrixX> qr(active.transpose());
    const int rank = static_cast<int>(qr.rank());
    if (rank >= n) return hess;
    const MatrixX q = qr.householderQ();
    z = q.rightCols(n - rank);
  }
  const Eigen::SelfAdjointEigenSolver<MatrixX> eig(z.transpose() * hess * z);
  const VectorX raise = (eig.eigenvalues().array().max(min_eigenvalue) - eig.eigenvalues().array()).matrix();
  const MatrixX zv = z * eig.eigenvectors();
  return hess + zv * raise.asDiagonal() * zv.transpose();
}

void DampedBfgs::update(const VectorX& s, const VectorX& y) {
  const double ss = s.squaredNorm();
  if (ss == 0.0) return;
  if (!scaled_) {
    const double sy = s.dot(y);
    if (sy > 0.0) b_ *= y.squaredNorm() / sy;
    scaled_ = true;
  }
  const VectorX bs = b_ * s;
  const double sbs = s.dot(bs);
  const double sy = s.dot(y);
  // Powell: replace y by θy + (1−θ)Bs so that sᵀy ≥ 0.2 sᵀBs.
  const double theta = sy >= 0.2 * sbs ? 1.0 : 0.8 * sbs / (sbs - sy);
  const VectorX r = theta * y + (1.0 - theta) * bs;
  b_ += r * r.transpose() / s.dot(r) - bs * bs.transpose() / sbs;
}

}  // namespace gaitopt
