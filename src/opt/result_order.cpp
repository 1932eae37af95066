#include "gaitopt/opt/result_order.hpp"

namespace gaitopt {
namespace {

// How far a run got: every level met (6) above an unmet level 5, 4, ..., 0.
int levelsMet(const OptimizationResult& r) { return r.unmet_level < 0 ? 6 : r.unmet_level; }

ResultRank rankOf(const OptimizationResult& r, Criterion c) {
  return {isOptimal(r), levelsMet(r), r.constraint_violation, criterionValue(r.evaluation, c)};
}

}  // namespace

bool betterRank(const ResultRank& a, const ResultRank& b, UnmetOrder unmet) {
  if (a.met != b.met) return a.met;
  if (a.met) return a.criterion < b.criterion;
  if (unmet == UnmetOrder::LevelThenViolation && a.levels_met != b.levels_met)
    return a.levels_met > b.levels_met;
  if (a.violation != b.violation) return a.violation < b.violation;
  return unmet == UnmetOrder::ViolationThenCriterion && a.criterion < b.criterion;
}

std::optional<double> resultCriterion(const OptimizationResult& r, Criterion c) {
  if (!r.evaluation.motion_computed || !r.evaluation.defined()) return std::nullopt;
  return criterionValue(r.evaluation, c);
}

bool betterResult(const OptimizationResult& a, const OptimizationResult& b, Criterion c,
                  UnmetOrder unmet) {
  return betterRank(rankOf(a, c), rankOf(b, c), unmet);
}

}  // namespace gaitopt
