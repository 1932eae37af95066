#pragma once
// Closing step of the full stage: Newton's method on the constraints active at the solver's
// last point, then a first-order optimality certificate there. SLSQP's quasi-Newton model,
// built across the kinks of the grid constraints, stops on small steps with the active rows
// still off by 1e-5…1e-4 on the richer parameterisations (speed (3.50), a clearance or torque
// node); restarts rebuild the same model and stop the same way. The active set at that point
// is the optimum's, so fixing it and solving g_A = −interior, speed = v by minimum-norm
// Gauss–Newton steps (in the scaled parameter norm of (3.78)) closes the stage in 2–3 exact
// Jacobians, moving the point by O(violation).
#include <optional>

#include "gaitopt/opt/evaluation_cache.hpp"
#include "gaitopt/opt/gait_problem.hpp"

namespace gaitopt {

struct ActiveSetClosing {
  GaitParameters x;
  bool feasible = false;        // every computed entry of levels 0–5 and the speed met at x
  int iterations = 0;           // Newton steps (one exact Jacobian each)
  int active = 0;               // rows of the last system, the speed included
  // KKT certificate at x with least-squares multipliers λ of the active rows:
  // ‖∇f + J_Aᵀλ‖ / ‖∇f‖ (scaled parameters) and the smallest inequality multiplier.
  double kkt_residual = 0.0;
  double min_multiplier = 0.0;
  bool certified(double tol) const {
    return feasible && kkt_residual <= tol && min_multiplier >= -tol;
  }
};

// `feasibility_tol`: a scaled entry (and |speed − v|) counts as met at this value (the
// optimiser's one tolerance); `interior`: the rows are aimed this far inside their bound.
ActiveSetClosing closeActiveSet(GaitEvaluationCache& cache, const GaitParameters& start,
                                Criterion criterion, const std::optional<double>& speed,
                                double feasibility_tol, double interior);

}  // namespace gaitopt
