#pragma once
// A small dense nonlinear program assembled from named pieces (after ifopt/TOWR): box-bounded
// variables, cost terms and constraint sets, each with its own derivative. Any piece may report
// that it cannot be evaluated at a point (an undefined walking step); the solver adapters then
// tell the solver to shorten its step.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

namespace gaitopt {

using VectorX = Eigen::VectorXd;
using MatrixX = Eigen::MatrixXd;

class CostTerm {
 public:
  virtual ~CostTerm() = default;
  virtual std::string name() const = 0;
  // false: undefined at x.
  virtual bool value(const VectorX& x, double& f) = 0;
  virtual bool gradient(const VectorX& x, Eigen::Ref<VectorX> grad) = 0;
  // Whether hessian() exists: a sum of squares' Gauss–Newton Hessian or an exact one.
  virtual bool hasHessian() const { return false; }
  virtual bool hessian(const VectorX&, Eigen::Ref<MatrixX>) { return false; }
};

class ConstraintSet {
 public:
  virtual ~ConstraintSet() = default;
  virtual std::string name() const = 0;
  virtual int size() const = 0;
  virtual void bounds(Eigen::Ref<VectorX> lower, Eigen::Ref<VectorX> upper) const = 0;
  virtual bool values(const VectorX& x, Eigen::Ref<VectorX> g) = 0;
  virtual bool jacobian(const VectorX& x, Eigen::Ref<MatrixX> jac) = 0;  // rows × variables
};

struct VariableSet {
  std::vector<std::string> names;
  VectorX lower, upper, initial;
  int size() const { return static_cast<int>(initial.size()); }
};

class NlpProblem {
 public:
  explicit NlpProblem(VariableSet variables) : variables_(std::move(variables)) {}
  void addCost(std::unique_ptr<CostTerm> term) { costs_.push_back(std::move(term)); }
  void addConstraints(std::unique_ptr<ConstraintSet> set);

  const VariableSet& variables() const { return variables_; }
  int numConstraints() const { return num_constraints_; }
  void constraintBounds(VectorX& lower, VectorX& upper) const;
  bool cost(const VectorX& x, double& f);
  bool costGradient(const VectorX& x, VectorX& grad);
  // Every cost term has a Hessian (CostTerm::hasHessian); costHessian sums them.
  bool hasCostHessian() const;
  bool costHessian(const VectorX& x, MatrixX& hess);
  bool constraints(const VectorX& x, VectorX& g);
  bool constraintJacobian(const VectorX& x, MatrixX& jac);
  // ∇ₓ(σ f + λᵀ g).
  bool lagrangianGradient(const VectorX& x, double sigma, const VectorX& lambda, VectorX& grad);
  // ∇²ₓ(σ f + λᵀ g) by forward differences of the exact gradients (n gradient evaluations),
  // symmetrised. The pieces carry first derivatives only: second-order AD through the step
  // evaluation would cost far more than n exact gradients.
  bool lagrangianHessian(const VectorX& x, double sigma, const VectorX& lambda, MatrixX& hess);
  // Name of the constraint set holding row `row`, and the row's index inside it.
  std::pair<std::string, int> constraintOrigin(int row) const;

 private:
  VariableSet variables_;
  std::vector<std::unique_ptr<CostTerm>> costs_;
  std::vector<std::unique_ptr<ConstraintSet>> constraints_;
  int num_constraints_ = 0;
};

}  // namespace gaitopt
