#pragma once
// summary.json of one evaluated walking step: status, criteria, timing, the parameters and one
// entry per constraint group (worst defined value, number violated). Written by
// `gaitopt evaluate`; the optimiser writes the same members plus its own (e.g. `solver`)
// through the `extra` hook or by calling writeGaitSummaryMembers on its own JsonWriter.
// Every quantity that was not computed is null, never NaN.
#include <functional>
#include <string>

#include "gaitopt/gait/evaluation.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/io/json_writer.hpp"

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

// Writes the summary members (status, failed_level, criteria, ..., constraints,
// max_violation, units) into the object the caller has opened on `w`.
void writeGaitSummaryMembers(JsonWriter& w, const GaitEvaluator& evaluator,
                             const GaitParameters& parameters,
                             const GaitEvaluation<double>& evaluation);

// The complete summary.json document (pretty-printed, ending with a newline). `extra`, when
// given, is called after the standard members to add more (w.key("solver").beginObject()...).
std::string gaitSummaryJson(const GaitEvaluator& evaluator, const GaitParameters& parameters,
                            const GaitEvaluation<double>& evaluation,
                            const std::function<void(JsonWriter&)>& extra = {});

}  // namespace gaitopt
