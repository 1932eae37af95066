#pragma once
// The Poincaré map of the zero dynamics (§4.2.2) for the closed loop of sim/hybrid_walk.hpp:
// the walk is started on the virtual constraints at SS start with α̇_iSS = v (q̇ = q*(α) v,
// outputs and their rates zero) and iterated in closed loop (full state, one step at a time).
// Per start: α̇ after the touchdown map (α̇_iDS, the "a" of (4.28)), the next α̇_iSS and α̇_iDS
// (Figs. 4.7 and 4.6), and the number of steps to reach the cycle. The cyclic motion is a fixed
// point of v → α̇_iSS(k+1), stable when the map's slope there is in (−1, 1) (§4.2.2.3); the
// region of attraction in one step / globally is the interval of starts around it that reach
// the cycle after one step / within `max_steps` (resolution: the grid spacing).
#include <string>
#include <vector>

#include "gaitopt/sim/poincare.hpp"

namespace gaitopt {

struct ZeroDynamicsRequest {
  double range = 0.3;  // starts v = α̇* (1 ± range), α̇* = the gait's α̇_iSS
  int points = 61;
  int max_steps = 10;
  double tolerance = 1e-6;  // |α̇_iSS(k) − α̇*| ≤ tolerance |α̇*|: on the cycle
  TouchdownMap touchdown = impulseFreeTouchdown();
};

struct ZeroDynamicsPoint {
  double alphad_iSS;
  double alphad_iDS, next_alphad_iSS, next_alphad_iDS;  // NaN when not reached
  int steps_to_cycle;  // −1: not within max_steps
  std::string outcome;  // of the walk from this start ("completed" or the failure)
};

struct ZeroDynamicsStudy {
  double fixed_point;  // α̇* at SS start (the gait's, checked by the map)
  double fixed_point_residual;  // |P(α̇*) − α̇*|
  double slope;  // dP/dα̇ at α̇* (central difference, step 1e-6 |α̇*|)
  bool stable;
  double one_step_low, one_step_high;  // α̇_iSS interval converging in one step
  double global_low, global_high;      // converging within max_steps
  double resolution;  // grid spacing of the intervals
  std::vector<ZeroDynamicsPoint> points;
};

ZeroDynamicsStudy studyZeroDynamics(const GaitEvaluation<double>& evaluation,
                                    const Model& controller, const Model& plant,
                                    const WalkRequest& base, const ZeroDynamicsRequest& request);

}  // namespace gaitopt
