#pragma once
// Optimal walking steps under the constraint hierarchy (§3.4). Default strategy "staged"
// (the fsqp-like scheme (3.76) the thesis recommends): first project the start onto levels 0–1,
// then onto levels 0–4 (nearest point in the scaled parameter norm, (3.78)), then solve the full
// problem; an iterate whose step cannot be computed is refused to the solver, which shortens
// its step. "direct" skips the two projections.
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "gaitopt/opt/evaluation_cache.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/feasibility.hpp"
#include "gaitopt/opt/gait_problem.hpp"
#include "gaitopt/opt/nlp_solver.hpp"

namespace gaitopt {

enum class HierarchyStrategy { Staged, Direct };
enum class Backend { Ipopt, NloptSlsqp, NloptCobyla };

struct SolverSettings {
  Backend backend = Backend::NloptSlsqp;  // measured faster than Ipopt here (docs/formats/optimizer-config.md)
  HierarchyStrategy hierarchy = HierarchyStrategy::Staged;
  int max_iter = 500;
  double tol = 1e-8;
  std::vector<std::pair<std::string, std::string>> ipopt_options;
  // Ipopt's Hessian of the Lagrangian: the dense BFGS measured fastest (docs/formats/optimizer-config.md).
  HessianMode hessian = HessianMode::DenseBfgs;
  int print_every = 1;
  // Exchange method for the grid constraints (only near-active entries in each NLP, re-checked
  // on the full grid after each solve); false: every grid entry in one NLP.
  bool constraint_exchange = false;  // measured: SLSQP stalls with it, Ipopt gains (docs/formats/optimizer-config.md)
  GradientMode gradients = GradientMode::Exact;
  // Phase-wise rows as the interpolant's maxima between the nodes (opt/gait_problem.hpp), so
  // the semi-infinite constraints hold on the whole phase; false: at the nodes only.
  bool between_nodes = true;
  // With between_nodes, also the DS rows (gait/ds_interval_maxima.hpp). Off at first: the
  // optimiser switches it on, warm from its point, once a solve ends with a DS constraint
  // unmet between the nodes (from the start, SLSQP measured worse local optima: docs/commands/optimize.md).
  bool ds_between_nodes = false;
  int max_restarts = 3;  // of the full stage, from the last point, when it ends unmet
  // An NLopt solve of the full stage that breaks down switches the run to Ipopt. After one of
  // its solves converged, only with this on (measured: more random starts of Chessé 0.85 end
  // optimal); off, SLSQP restarts from its last point (the sweep, whose speeds without an
  // optimum get the elastic problem and retries: docs/commands/sweep.md).
  bool ipopt_after_convergence = true;
  // When the full stage still ends with an unmet constraint: the nearest point meeting every
  // level and the speed, then the full stage again from there (docs/commands/optimize.md). Off
  // by default: it adds an Ipopt projection to every infeasible run (sweeps, infeasible
  // speeds); on in globalSearch (--global, bench_optimize --random-starts), where unmet starts are
  // the common failure.
  bool restore_feasibility = false;
  // Progress hook: the stage's label, the parameters of the solver's last point, its iteration.
  std::function<void(const std::string& stage, const GaitParameters& p, int iteration)>
      on_iteration;
};

struct OptimizationRequest {
  Criterion criterion = Criterion::Torque;
  std::optional<double> speed;  // m/s; free speed when empty
  GaitParameters initial;
  SolverSettings solver;
};

struct StageReport {
  std::string name;
  NlpStatus status;
  int iterations;
};

// How a run ended under the one feasibility verdict (gait/feasibility.hpp): Optimal (feasible,
// the solver converged), Infeasible (a constraint unmet, whatever the solver says), MaxIter or
// Failed (feasible, the solver stopped at its iteration limit or failed).
enum class OptimizationStatus { Optimal, Infeasible, MaxIter, Failed };

// "optimal", "infeasible", "max_iter", "failed": the names in summary.json and sweep.csv.
const char* optimizationStatusName(OptimizationStatus s);
// The status called `name`; empty for any other text.
std::optional<OptimizationStatus> parseOptimizationStatus(const std::string& name);
std::ostream& operator<<(std::ostream& out, OptimizationStatus s);

struct OptimizationResult {
  GaitParameters parameters;
  // Where the run's last solve ended: `parameters` unless the run returned a better point it
  // met (a last point unmet); retries start near it.
  GaitParameters last_parameters;
  GaitEvaluation<double> evaluation;
  OptimizationStatus status = OptimizationStatus::Failed;
  int iterations = 0;
  int function_evaluations = 0, gradient_evaluations = 0;
  double wall_time_s = 0.0;
  double constraint_violation = 0.0;  // max over all levels and the speed, unscaled
  int unmet_level = -1;               // lowest level with an unmet constraint
  std::vector<std::string> unmet_constraints;
  // Worst scaled phase-wise value on the 10× finer check (gait/feasibility.hpp).
  double between_nodes_worst = 0.0;
  // Without dry friction: the torque envelope with the robot's Coulomb friction (its message
  // names the group and the excess; gait/feasibility.hpp).
  RobotFrictionCheck robot_friction;
  std::vector<StageReport> stages;
};

bool isOptimal(const OptimizationResult& r);

const char* backendName(Backend b);
const char* strategyName(HierarchyStrategy s);

OptimizationResult optimizeGait(const GaitEvaluator& evaluator, const OptimizationRequest& request,
                                std::ostream* log = nullptr);

}  // namespace gaitopt
