#pragma once
// One step evaluation shared by every cost term and constraint set of an optimisation problem
// at the current point (the solver asks for f, ∇f, g and ∂g separately at the same x).
#include <optional>

#include "gaitopt/gait_evaluator.hpp"

namespace gaitopt {

class GaitEvaluationCache {
 public:
  explicit GaitEvaluationCache(const GaitEvaluator& evaluator) : evaluator_(evaluator) {}
  const GaitEvaluator& evaluator() const { return evaluator_; }
  const GaitEvaluation<double>& values(const GaitParameters& p);
  const GaitGradient& gradient(const GaitParameters& p);
  int valueEvaluations() const { return value_count_; }
  int gradientEvaluations() const { return gradient_count_; }

 private:
  const GaitEvaluator& evaluator_;
  std::optional<GaitParameters> value_at_, gradient_at_;
  GaitEvaluation<double> values_;
  GaitGradient gradient_;
  int value_count_ = 0, gradient_count_ = 0;
};

}  // namespace gaitopt
