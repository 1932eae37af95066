#pragma once
// Solver back-ends for an NlpProblem: Ipopt (interior point, limited-memory quasi-Newton
// Hessian) and NLopt (SLSQP with gradients, COBYLA derivative-free). The adapters only
// translate; the problem's pieces hold all the physics.
#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "gaitopt/opt/nlp_problem.hpp"

namespace gaitopt {

enum class NlpStatus { Solved, Infeasible, MaxIterations, Failed };

// Where Ipopt's Hessian of the Lagrangian comes from.
enum class HessianMode {
  LimitedMemory,  // Ipopt's own L-BFGS (low-rank, solved through extra back-solves)
  DenseBfgs,      // a dense damped BFGS of the Lagrangian kept by the adapter (n is small)
  Exact,          // finite differences of the exact gradients, positive-definite on the null
                  // space of the active constraints
  ExactUnmodified, // the same, indefinite: left to Ipopt's inertia correction
  GaussNewton      // the cost's own Hessian where every term has one (C_Γ: 2 JᵀJ of its
                   // residuals; the distance: exact) plus a damped BFGS of the remainder
                   // (constraint curvature); a cost without one: DenseBfgs
};

// Bound and constraint multipliers: a solve's final ones, or a warm start for the next solve.
struct NlpMultipliers {
  VectorX z_lower, z_upper, lambda;
  bool empty() const { return lambda.size() == 0 && z_lower.size() == 0; }
};

const char* nlpStatusName(NlpStatus s);

struct NlpSettings {
  int max_iter = 500;
  double tol = 1e-6;                 // optimality tolerance
  double constraint_tol = 1e-7;      // feasibility tolerance on the scaled constraints
  std::vector<std::pair<std::string, std::string>> ipopt_options;  // passed through
  HessianMode hessian = HessianMode::LimitedMemory;  // Ipopt only
  // Ipopt only: start from these multipliers (sizes n, n, m) with a warm-started interior point.
  NlpMultipliers warm_start;
  std::string label;                 // hierarchy stage, for the progress lines
  int print_every = 1;               // progress line every k iterations (0: silent)
  std::ostream* log = nullptr;
  // Called after each iteration (Ipopt) or cost evaluation (NLopt) with the last point whose
  // cost was evaluated, whatever `log` and `print_every` (the CLI's progress in user units).
  std::function<void(const VectorX& x, int iteration)> on_iteration;
};

struct NlpSolution {
  VectorX x;
  NlpStatus status = NlpStatus::Failed;
  int iterations = 0;
  double objective = 0.0;
  NlpMultipliers multipliers;  // Ipopt only
  std::string message;
};

// Thread-safe: concurrent calls run one after the other.
NlpSolution solveWithIpopt(NlpProblem& problem, const NlpSettings& settings);
// The first option key Ipopt rejects (unknown key or bad value), or "" if all are accepted.
std::string rejectedIpoptOption(const std::vector<std::pair<std::string, std::string>>& options);
// Whether Ipopt can solve with linear solver `name` (e.g. "ma57" needs the HSL library at run
// time): a one-variable problem is solved with it.
bool ipoptLinearSolverAvailable(const std::string& name);

enum class NloptMethod { Slsqp, Cobyla };
NlpSolution solveWithNlopt(NlpProblem& problem, const NlpSettings& settings, NloptMethod method);

}  // namespace gaitopt
