#include "gaitopt/gait_evaluation_cache.hpp"

namespace gaitopt {

const GaitEvaluation<double>& GaitEvaluationCache::values(const GaitParameters& p) {
  if (gradient_at_ && *gradient_at_ == p) return gradient_.value;
  if (!value_at_ || *value_at_ != p) {
    values_ = evaluator_.evaluate(p);
    value_at_ = p;
    ++value_count_;
  }
  return values_;
}

const GaitGradient& GaitEvaluationCache::gradient(const GaitParameters& p) {
  if (!gradient_at_ || *gradient_at_ != p) {
    gradient_ = evaluator_.evaluateWithGradient(p);
    gradient_at_ = p;
    ++gradient_count_;
  }
  return gradient_;
}

}  // namespace gaitopt
