#include "gaitopt/opt/nlp_problem.hpp"

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

std::pair<std::string, int> NlpProblem::constraintOrigin(int row) const {
  for (const auto& set : constraints_) {
    if (row < set->size()) return {set->name(), row};
    row -= set->size();
  }
  return {"", -1};
}

}  // namespace gaitopt
