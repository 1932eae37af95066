#include "gaitopt/gait/constraint_summary.hpp"

#include <cmath>
#include <limits>

namespace gaitopt {

ConstraintGroupSummary summarizeConstraintGroup(const ConstraintGroup& group,
                                                const GaitEvaluation<double>& e,
                                                double tolerance) {
  ConstraintGroupSummary s;
  double worst = -std::numeric_limits<double>::infinity();
  bool nan = false;  // a Defined NaN would be an evaluator bug: report the group as null
  for (int k = group.offset; k < group.offset + group.count; ++k) {
    if (e.state[k] != ConstraintState::Defined) continue;
    const double g = e.g[k];
    ++s.defined;
    nan = nan || std::isnan(g);
    if (g > worst) worst = g;
    if (!(g <= tolerance)) ++s.violated;
  }
  s.value = s.defined > 0 && !nan ? worst : std::numeric_limits<double>::quiet_NaN();
  return s;
}

double maxDefinedViolation(const GaitEvaluation<double>& e) {
  double worst = 0.0;
  for (std::size_t k = 0; k < e.g.size(); ++k) {
    if (e.state[k] == ConstraintState::Defined && e.g[k] > worst) worst = e.g[k];
  }
  return worst;
}

bool zeroDynamicsComputed(const GaitEvaluator& ev, const GaitEvaluation<double>& e) {
  const ConstraintGroup& f = ev.layout()[kFPositive];
  return f.count > 0 && e.state[f.offset] != ConstraintState::NotComputed;
}

}  // namespace gaitopt
