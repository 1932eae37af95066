#include "gaitopt/opt/result_order.hpp"

namespace gaitopt {
namespace {

// How far a run got: every level met (6) above an unmet level 5, 4, ..., 0.
int levelsMet(const OptimizationResult& r) { return r.unmet_level < 0 ? 6 : r.unmet_level; }

}  // namespace

std::optional<double> resultCriterion(const OptimizationResult& r, Criterion c) {
  if (!r.evaluation.motion_computed || !r.evaluation.defined()) return std::nullopt;
  return criterionValue(r.evaluation, c);
}

bool betterResult(const OptimizationResult& a, const OptimizationResult& b, Criterion c,
                  UnmetOrder unmet) {
  if (isOptimal(a) != isOptimal(b)) return isOptimal(a);
  if (isOptimal(a)) return criterionValue(a.evaluation, c) < criterionValue(b.evaluation, c);
  if (unmet == UnmetOrder::LevelThenViolation && levelsMet(a) != levelsMet(b))
    return levelsMet(a) > levelsMet(b);
  return a.constraint_violation < b.constraint_violation;
}

}  // namespace gaitopt
