#pragma once
// Which of two results of one problem is better: the one ordering of gaitopt, for the points a
// solve met (the optimizer returns the best when its last point breaks the verdict), the
// random starts, the attempts at one speed of a sweep and a global search in which no start
// converged. A result that meets the problem's standard beats any other and two such compare
// by the criterion; two others compare as `unmet` says. Strict: on equal standing it is false,
// so a caller that replaces only a worse result keeps the earlier one.
#include <optional>

#include "gaitopt/opt/optimizer.hpp"

namespace gaitopt {

enum class UnmetOrder {
  Violation,               // the smaller violation
  ViolationThenCriterion,  // the smaller violation, then the smaller criterion
  LevelThenViolation,      // the more levels of the hierarchy met, then the smaller violation
};

// Where a result stands: `met` the standard (the status optimal, or the feasibility verdict
// for a point), the levels met (6 = all), its violation and criterion.
struct ResultRank {
  bool met;
  int levels_met;
  double violation;
  double criterion;
};

bool betterRank(const ResultRank& a, const ResultRank& b, UnmetOrder unmet);

// The criterion of a result whose step is defined with its motion computed; empty otherwise.
std::optional<double> resultCriterion(const OptimizationResult& r, Criterion criterion);

// betterRank of two finished results: met when optimal, violation the result's.
bool betterResult(const OptimizationResult& a, const OptimizationResult& b, Criterion criterion,
                  UnmetOrder unmet);

}  // namespace gaitopt
