#pragma once
// Non-negative least squares  min ‖A x − b‖  s.t.  x ≥ 0  by Lawson & Hanson's active-set
// method (Solving Least Squares Problems, 1974, ch. 23): the multipliers of the inequality rows
// active at a point, which are ≥ 0 at a first-order point but not unique when more rows are
// active than there are variables (a plain least-squares solution can then be negative).
// Written here because Debian's Eigen (3.4.0) ships no NNLS module and NLopt's SLSQP returns
// no multipliers.
#include <Eigen/Core>

namespace gaitopt {

struct NnlsResult {
  Eigen::VectorXd x;
  double residual = 0.0;  // ‖A x − b‖
  bool converged = false;  // the KKT conditions hold (within the iteration limit 3·cols)
};

NnlsResult solveNonnegativeLeastSquares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

}  // namespace gaitopt
