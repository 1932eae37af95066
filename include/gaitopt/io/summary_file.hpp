#pragma once
// summary.json of one evaluated walking step: status, criteria, timing, the parameters and one
// entry per constraint group (worst defined value, number violated). Written by
// `gaitopt evaluate`; the optimiser writes the same members plus its own (e.g. `solver`)
// through the `extra` hook or by calling writeGaitSummaryMembers on its own JsonWriter.
// Every quantity that was not computed is null, never NaN.
#include <functional>
#include <string>
#include <vector>

#include "gaitopt/gait/evaluation.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {

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

// The `overrides` member (the command line's KEY=VALUE in order), when there are any.
void writeOverridesJson(JsonWriter& w, const std::vector<std::string>& overrides);

}  // namespace gaitopt
