#pragma once
// A closed-loop walk request configured for a gait as `gaitopt simulate` does it.
#include "gaitopt/sim/hybrid_walk.hpp"

namespace gaitopt::test {

inline WalkRequest gaitRequest(const GaitOptions& options, int steps) {
  WalkRequest req;
  req.steps = steps;
  configureForGait(options, req);
  return req;
}

}  // namespace gaitopt::test
