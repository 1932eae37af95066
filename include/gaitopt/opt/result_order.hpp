#pragma once
// Which of two optimisation results of one problem is better, for the callers that keep the
// best of several runs: random starts, the attempts at one speed of a sweep, a global search in
// which no start converged. An optimal result beats any other and two optimal ones compare by
// the criterion; two others compare as `unmet` says. Strict: on equal standing it is false, so
// a caller that replaces only a worse result keeps the earlier one.
#include <optional>

#include "gaitopt/opt/optimizer.hpp"

namespace gaitopt {

enum class UnmetOrder {
  Violation,           // the smaller constraint violation
  LevelThenViolation,  // the run that met more levels of the hierarchy, then the smaller violation
};

// The criterion of a result whose step is defined with its motion computed; empty otherwise.
std::optional<double> resultCriterion(const OptimizationResult& r, Criterion criterion);

bool betterResult(const OptimizationResult& a, const OptimizationResult& b, Criterion criterion,
                  UnmetOrder unmet);

}  // namespace gaitopt
