#include "gaitopt/sim/cycle_convergence.hpp"

#include <cmath>

namespace gaitopt {

bool convergedToCycle(const WalkResult& r, double alphadot_iSS) {
  const std::size_t n = r.steps.size();
  if (r.outcome != WalkOutcome::Completed || n < 2) return false;
  return std::abs(r.steps[n - 1].alphad_start - alphadot_iSS) < 1e-6 &&
         std::abs(r.steps[n - 1].max_output_error - r.steps[n - 2].max_output_error) < 1e-6;
}

bool tracksReference(const WalkResult& r, double alphadot_iSS) {
  return convergedToCycle(r, alphadot_iSS) && r.steps.back().max_output_error < 1e-6;
}

}  // namespace gaitopt
