#pragma once
// Second-order models for the interior-point solver: a dense damped BFGS approximation of the
// Hessian of the Lagrangian, and the modification that makes an exact (indefinite) Hessian
// positive-definite where it matters, on the null space of the active constraints.
#include "gaitopt/opt/nlp_problem.hpp"

namespace gaitopt {

// H + Z (V (max(D, ε) − D) Vᵀ) Zᵀ where Z spans the null space of `active` (rows: gradients of
// the active constraints) and V D Vᵀ = Zᵀ H Z: the reduced Hessian's eigenvalues are raised to
// at least ε, the range-space part (which the constraints already fix) is left alone. An empty
// `active` modifies every eigenvalue of H.
MatrixX positiveOnNullSpace(const MatrixX& hess, const MatrixX& active, double min_eigenvalue);

// BFGS with Powell's damping (the update of SLSQP): stays positive-definite when the
// Lagrangian's curvature along a step is negative. Starts from the identity, rescaled by
// yᵀy / sᵀy at the first update (Shanno–Phua).
class DampedBfgs {
 public:
  explicit DampedBfgs(int n) : b_(MatrixX::Identity(n, n)) {}
  void update(const VectorX& s, const VectorX& y);
  const MatrixX& matrix() const { return b_; }

 private:
  MatrixX b_;
  bool scaled_ = false;
};

}  // namespace gaitopt
