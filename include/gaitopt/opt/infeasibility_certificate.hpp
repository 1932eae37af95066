#pragma once
// Evidence that a walking speed cannot be met: the elastic (phase-1) problem
//   min s  over (p, s)  s.t.  g_k(p) / scale_k ≤ s  for every level-5 row (between the nodes
//   too),  levels 0–4 held,  speed(p) = v,
// started from the best point an optimisation reached, solved at the nodes first (smooth rows;
// a step that cannot meet them at the nodes cannot meet them between), then, when they can be
// met there, with the rows between the nodes (opt/gait_problem.hpp), and, when those can be met
// but the point still breaks the verdict's 10× finer check, with the level-5 rows of that finer
// grid (gait/feasibility.hpp: nested in the nodes, so the verdict's own rows). Its optimum s*
// is the smallest worst scaled violation reachable from there; s* > 0 at a first-order point
// shows the speed locally infeasible (the problem is not convex: another region of the parameters
// is not excluded). Since ∂/∂s of the Lagrangian gives Σ λ_k = 1, each row's multiplier λ_k is
// its share of the blockage: relaxing that row's bound by ε (scaled) lowers s* by λ_k ε. The
// multipliers are those of the rows active at the point, by non-negative least squares (SLSQP
// returns none). s is bounded below by 0: s* = 0 means every row can be met (no evidence; the
// speed's attempts failed for another reason, the solver's; `feasible` says whether the point
// reached meets the whole verdict, a start for another attempt).
#include <optional>
#include <string>
#include <vector>

#include "gaitopt/gait/evaluator.hpp"

namespace gaitopt {

struct BlockingConstraint {
  int entry = -1;           // layout entry (gait/constraints.hpp)
  std::string name;         // constraintRowName, " (between nodes)" for such a row (a row of
                            // the finer grid: that of the interval holding it)
  double multiplier = 0.0;  // λ_k of the elastic problem (the multipliers sum to 1)
  double value = 0.0;       // g_k at the elastic optimum, in `unit` (> 0: unmet)
  std::string unit;
};

struct InfeasibilityCertificate {
  GaitParameters x;              // the elastic problem's last point
  bool converged = false;        // a first-order point, x not feasible (the multipliers hold)
  bool feasible = false;         // the one verdict (gait/feasibility.hpp) holds at x
  double min_violation = 0.0;    // s*: the worst scaled level-5 row at x, of the last problem
  std::vector<BlockingConstraint> blocking;  // λ ≥ kBlockingMultiplier, largest first
  int iterations = 0;
  double wall_time_s = 0.0;
  // Proven infeasible (locally): a first-order point of the elastic problem with s* beyond
  // the feasibility tolerance and at least one blocking row.
  bool infeasible() const {
    return converged && !feasible && min_violation > kFeasibilityTolerance && !blocking.empty();
  }
};

// Rows with a smaller share are not listed as blocking.
constexpr double kBlockingMultiplier = 1e-3;

// The constraint group holding layout entry `entry` (−1: none).
int constraintGroupOf(const ConstraintLayout& layout, int entry);
// Name of layout entry `entry` in the user's terms: group, joint or foot and side, and phase
// node ("torque_envelope_ds hip 2 upper at DS node 4"). The certificate adds " (between
// nodes)" for the rows held between the nodes: node k's row stands for the interval from node
// k to node k + 1 (the last node for itself).
std::string constraintRowName(const ConstraintLayout& layout, int entry);

// The elastic problem from `start` (its motion must be computable) at the target `speed`
// (none: free speed), solved by SLSQP with `max_iter` iterations per solve (at most four
// solves per problem: restarts while they lower s*).
InfeasibilityCertificate minimiseViolation(const GaitEvaluator& evaluator,
                                           const GaitParameters& start,
                                           const std::optional<double>& speed, int max_iter = 300);

}  // namespace gaitopt
