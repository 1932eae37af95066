#pragma once
// What summary.json and the command-line reports say about a step's constraints: the worst
// value of a group, the largest violation, and whether the zero dynamics ran.
#include "gaitopt/gait/evaluation.hpp"
#include "gaitopt/gait/evaluator.hpp"

namespace gaitopt {

// Worst value of one constraint group over its entries whose state is Defined.
struct ConstraintGroupSummary {
  double value = 0.0;  // max over Defined entries (NaN if none is Defined)
  int defined = 0;     // entries whose state is Defined
  int violated = 0;    // Defined entries > tolerance
};

// `tolerance`: kFeasibilityTolerance × the group's scale in summary.json (gait/feasibility.hpp).
ConstraintGroupSummary summarizeConstraintGroup(const ConstraintGroup& group,
                                                const GaitEvaluation<double>& evaluation,
                                                double tolerance = 0.0);

// max(0, max over every Defined entry): the largest violation that counts.
double maxDefinedViolation(const GaitEvaluation<double>& evaluation);

// Whether T_SS, speed and alphadot_fSS were computed, i.e. the zero dynamics ran (levels 0–1
// hold; the f_positive group has been evaluated).
bool zeroDynamicsComputed(const GaitEvaluator& evaluator,
                          const GaitEvaluation<double>& evaluation);

}  // namespace gaitopt
