#include "gaitopt/opt/nlp_problem.hpp"

#include <algorithm>
#include <cmath>

namespace gaitopt {

void NlpProblem::addConstraints(std::unique_ptr<ConstraintSet> set) {
  num_constraints_ += set->size();
  constraints_.push_back(std::move(set));
}

void NlpProblem::constraintBounds(VectorX& lower, VectorX& upper) const {
  lower.resize(num_constraints_);
  upper.resize(num_constraints_);
  int row = 0;
  for (const auto& set : constraints_) {
    set->bounds(lower.segment(row, set->size()), upper.segment(row, set->size()));
    row += set->size();
  }
}

bool NlpProblem::cost(const VectorX& x, double& f) {
  f = 0.0;
  for (const auto& term : costs_) {
    double v = 0.0;
    if (!term->value(x, v)) return false;
    f += v;
  }
  return true;
}

bool NlpProblem::costGradient(const VectorX& x, VectorX& grad) {
  grad = VectorX::Zero(x.size());
  VectorX g(x.size());
  for (const auto& term : costs_) {
    if (!term->gradient(x, g)) return false;
    grad += g;
  }
  return true;
}

bool NlpProblem::hasCostHessian() const {
  return std::all_of(costs_.begin(), costs_.end(),
                     [](const std::unique_ptr<CostTerm>& t) { return t->hasHessian(); });
}

bool NlpProblem::costHessian(const VectorX& x, MatrixX& hess) {
  hess = MatrixX::Zero(x.size(), x.size());
  MatrixX h(x.size(), x.size());
  for (const auto& term : costs_) {
    if (!term->hessian(x, h)) return false;
    hess += h;
  }
  return true;
}

bool NlpProblem::constraints(const VectorX& x, VectorX& g) {
  g.resize(num_constraints_);
  int row = 0;
  for (const auto& set : constraints_) {
    if (!set->values(x, g.segment(row, set->size()))) return false;
    row += set->size();
  }
  return true;
}

bool NlpProblem::constraintJacobian(const VectorX& x, MatrixX& jac) {
  jac.resize(num_constraints_, x.size());
  int row = 0;
  for (const auto& set : constraints_) {
    if (!set->jacobian(x, jac.middleRows(row, set->size()))) return false;
    row += set->size();
  }
  return true;
}

bool NlpProblem::lagrangianGradient(const VectorX& x, double sigma, const VectorX& lambda,
                                    VectorX& grad) {
  MatrixX jac;
  if (!costGradient(x, grad) || !constraintJacobian(x, jac)) return false;
  grad = sigma * grad + jac.transpose() * lambda;
  return true;
}

// Step h = 1e-6·max(1, |x_j|) (the square root of the gradients' relative accuracy, ~1e-12 for
// the AD gradients of the integrated step); a side that cannot be evaluated is tried backwards.
bool NlpProblem::lagrangianHessian(const VectorX& x, double sigma, const VectorX& lambda,
                                   MatrixX& hess) {
  const int n = static_cast<int>(x.size());
  VectorX g0, g1;
  if (!lagrangianGradient(x, sigma, lambda, g0)) return false;
  hess.resize(n, n);
  for (int j = 0; j < n; ++j) {
    double h = 1e-6 * std::max(1.0, std::abs(x(j)));
    if (variables_.lower(j) == variables_.upper(j)) {
      hess.col(j).setZero();
      continue;
    }
    VectorX xp = x;
    xp(j) += h;
    if (!lagrangianGradient(xp, sigma, lambda, g1)) {
      h = -h;
      xp(j) = x(j) + h;
      if (!lagrangianGradient(xp, sigma, lambda, g1)) return false;
    }
    hess.col(j) = (g1 - g0) / h;
  }
  hess = 0.5 * (hess + hess.transpose()).eval();
  return true;
}

std::pair<std::string, int> NlpProblem::constraintOrigin(int row) const {
  for (const auto& set : constraints_) {
    if (row < set->size()) return {set->name(), row};
    row -= set->size();
  }
  return {"", -1};
}

}  // namespace gaitopt
