#include "gaitopt/opt/optimizer.hpp"

#include <algorithm>
#include <Eigen/Cholesky>
#include <chrono>
#include <cmath>
#include <limits>

#include "gaitopt/gait/feasibility.hpp"

namespace gaitopt {
namespace {

// Exchange method for the semi-infinite constraints: a grid entry joins the NLP once its
// scaled value exceeds −kScreenThreshold; the full grid is re-checked after each solve.
constexpr double kScreenThreshold = 0.3;
constexpr int kMaxExchangeRounds = 8;
// Projections aim this far inside the lower levels (scaled units): a point on their boundary
// (e.g. a DS with the minimum α range) is a poor start for the next stage.
constexpr double kProjectionInterior = 0.05;
// Full stage: strictly inside levels 0–4, whose failure would stop the motion's computation;
// level 5 only to the solver's own tolerance, below the shared feasibility tolerance.
constexpr double kInterior = 1e-6;
// Exchange method on continuous α and t: when a local maximum of the phase-wise constraints on
// the 10× refined grid exceeds kBetweenNodesThreshold (scaled), every local maximum within
// kNearActive of active becomes an extra constraint point, then the problem is re-solved. The
// near-active ones too: the optimum moves when the violated ones are added, and a maximum just
// inside would then be violated, costing one more solve (measured: 4 solves instead of 2).
constexpr double kBetweenNodesThreshold = 0.25 * kFeasibilityTolerance;
constexpr double kNearActive = 1e-3;
constexpr int kMaxBetweenNodesRounds = 8;  // a maximum that drifts needs more (coarse grids)
constexpr double kMinPointSpacing = 1e-4;  // in the Chebyshev coordinate of the phase
// Restoration after new points: Gauss–Newton steps on the rows within this (scaled) band.
constexpr int kRestorationSteps = 8;
constexpr double kRestorationBand = 1e-6;

NlpSolution solve(NlpProblem& problem, const SolverSettings& s, const std::string& label,
                  std::ostream* log) {
  NlpSettings ns;
  ns.max_iter = s.max_iter;
  ns.tol = s.tol;
  ns.ipopt_options = s.ipopt_options;
  ns.label = label;
  ns.print_every = s.print_every;
  ns.log = log;
  switch (s.backend) {
    case Backend::NloptSlsqp: return solveWithNlopt(problem, ns, NloptMethod::Slsqp);
    case Backend::NloptCobyla: return solveWithNlopt(problem, ns, NloptMethod::Cobyla);
    default: return solveWithIpopt(problem, ns);
  }
}

double scaledValue(const GaitEvaluator& ev, const GaitEvaluation<double>& e, int k) {
  return e.g[k] / ev.layout().scaleOf(k);
}

// Adds to `entries` the grid entries of levels ≤ max_level that are violated, close to active,
// or not computable at the evaluation; returns how many were added.
int screenEntries(const GaitEvaluator& ev, const GaitEvaluation<double>& e, int max_level,
                  std::vector<int>& entries) {
  std::vector<bool> in(ev.layout().size(), false);
  for (int k : entries) in[k] = true;
  int added = 0;
  for (int k : hierarchyEntries(ev.layout(), max_level))
    if (!in[k] && (e.state[k] == ConstraintState::NotComputed ||
                   scaledValue(ev, e, k) > -kScreenThreshold)) {
      entries.push_back(k);
      ++added;
    }
  std::sort(entries.begin(), entries.end());
  return added;
}

// Solves one stage with the exchange method; `build` adds the cost (and speed) to a problem.
template <class Build>
NlpSolution solveStage(GaitEvaluationCache& cache, const GaitParameters& start, int max_level,
                       double interior, double level5_interior, const SolverSettings& s,
                       const std::string& label, std::ostream* log, OptimizationResult& result,
                       const Build& build) {
  const GaitEvaluator& ev = cache.evaluator();
  std::vector<int> entries;
  if (s.constraint_exchange)
    screenEntries(ev, cache.values(start), max_level, entries);
  else
    entries = hierarchyEntries(ev.layout(), max_level);
  NlpSolution sol;
  sol.x = start;
  for (int round = 0; round < kMaxExchangeRounds; ++round) {
    NlpProblem problem(gaitVariables(ev.model(), sol.x, ev.options().parameterisation));
    build(problem);
    problem.addConstraints(makeHierarchyConstraints(cache, entries, interior, level5_interior));
    const std::string name = label + " (" + std::to_string(entries.size()) + " grid entries)";
    const NlpSolution next = solve(problem, s, name, log);
    result.stages.push_back({name, next.status, next.iterations});
    result.iterations += next.iterations;
    sol = next;
    if (screenEntries(ev, cache.values(sol.x), max_level, entries) == 0) break;
  }
  return sol;
}

// Nearest point (scaled norm) satisfying the levels ≤ max_level, (3.78).
GaitParameters project(GaitEvaluationCache& cache, const GaitParameters& start, int max_level,
                       const SolverSettings& s, const std::string& label, std::ostream* log,
                       OptimizationResult& result) {
  // Ipopt for every projection: it refuses undefined trial points natively (eval returns
  // false), where SLSQP's backtracking on a huge cost measured unreliable.
  SolverSettings projection = s;
  projection.backend = Backend::Ipopt;
  return solveStage(cache, start, max_level, kProjectionInterior, 0.0, projection, label, log, result,
                    [&](NlpProblem& problem) { problem.addCost(makeDistanceCost(start, cache.evaluator().options().parameterisation)); })
      .x;
}

// Every node entry and the speed within the feasibility tolerance (the between-node check is
// the outer exchange loop's business).
bool meetsAll(const OptimizationRequest& req, const GaitEvaluation<double>& e) {
  return e.motion_computed && e.failed_level < 0 &&
         (!req.speed || std::abs(e.speed - *req.speed) <= kFeasibilityTolerance);
}

// The final verdict is the shared one (gait/feasibility.hpp): an unmet constraint, also between
// nodes, is "infeasible" whatever the solver says; a feasible point is "optimal" only if the
// solver also converged.
void classify(const GaitEvaluator& ev, const OptimizationRequest& req, NlpStatus solver_status,
              OptimizationResult& r) {
  const FeasibilityVerdict v = feasibilityVerdict(ev, r.parameters, r.evaluation, req.speed);
  r.constraint_violation = v.max_violation;
  r.unmet_level = v.failed_level;
  r.unmet_constraints = v.unmet_groups;
  r.between_nodes_worst_scaled = v.between_nodes.worst_scaled;
  if (!v.feasible) r.status = "infeasible";
  else if (solver_status == NlpStatus::Solved) r.status = "optimal";
  else if (solver_status == NlpStatus::MaxIterations) r.status = "max_iter";
  else r.status = "failed";
}

}  // namespace

const char* backendName(Backend b) {
  return b == Backend::Ipopt ? "ipopt" : b == Backend::NloptSlsqp ? "nlopt_slsqp" : "nlopt_cobyla";
}

const char* strategyName(HierarchyStrategy s) {
  return s == HierarchyStrategy::Staged ? "staged" : "direct";
}

namespace {

// Staged strategy: project onto levels 0–1, then 0–4, as long as the evaluator finds a failed
// level below 5 (a projection that stalls is restarted from its own point).
GaitParameters repairLowerLevels(GaitEvaluationCache& cache, GaitParameters p,
                                 const OptimizationRequest& req, std::ostream* log,
                                 OptimizationResult& r) {
  for (int pass = 0; pass < 2 * (req.solver.max_restarts + 1); ++pass) {
    const int failed = cache.values(p).failed_level;
    if (failed < 0 || failed > 4) break;
    const int target = failed <= 1 ? 1 : 4;
    p = project(cache, p, target, req.solver, "levels 0-" + std::to_string(target), log, r);
  }
  return p;
}

// Largest scaled violation over the computed entries and the speed; +∞ if the motion is not
// computed.
double infeasibility(GaitEvaluationCache& cache, const GaitParameters& p,
                     const OptimizationRequest& req) {
  const GaitEvaluator& ev = cache.evaluator();
  const GaitEvaluation<double>& e = cache.values(p);
  if (!e.motion_computed || (e.failed_level >= 0 && e.failed_level < 5))
    return std::numeric_limits<double>::infinity();
  double worst = req.speed ? std::abs(e.speed - *req.speed) : 0.0;
  for (int k = 0; k < ev.layout().size(); ++k) worst = std::max(worst, scaledValue(ev, e, k));
  return worst;
}

// After new points between nodes the optimum is slightly infeasible (~1e-4 scaled), and SLSQP
// from there stalls: with its fresh quasi-Newton model its first steps are long, and its ℓ1
// merit, weighted by the new rows' zero multipliers, takes it back to the infeasible point
// (measured; an Ipopt projection instead took 10–40 s). So first a few Gauss–Newton steps of
// minimum scaled norm (3.78) onto the near-active rows and the speed, then SLSQP from there.
GaitParameters restore(GaitEvaluationCache& cache, GaitParameters p,
                       const OptimizationRequest& req) {
  const GaitEvaluator& ev = cache.evaluator();
  const VariableSet vars = gaitVariables(ev.model(), p, ev.options().parameterisation);
  const GaitParameters w = parameterScales(ev.options().parameterisation);
  for (int it = 0; it < kRestorationSteps; ++it) {
    const GaitGradient& gr = cache.gradient(p);
    if (!gr.value.motion_computed) break;
    std::vector<int> rows;
    bool violated = req.speed && std::abs(gr.value.speed - *req.speed) > 0.1 * kFeasibilityTolerance;
    for (int k = 0; k < ev.layout().size(); ++k) {
      if (gr.value.state[k] == ConstraintState::NotComputed) continue;
      const double scaled = scaledValue(ev, gr.value, k);
      if (scaled > -kRestorationBand) rows.push_back(k);
      violated = violated || scaled > 0.1 * kFeasibilityTolerance;
    }
    if (!violated) break;
    const int m = static_cast<int>(rows.size()) + (req.speed ? 1 : 0);
    MatrixX a(m, p.size());
    VectorX rhs(m);
    for (int i = 0; i < static_cast<int>(rows.size()); ++i) {
      const double scale = ev.layout().scaleOf(rows[i]);
      a.row(i) = gr.dg.row(rows[i]).cwiseProduct(w.transpose()) / scale;
      rhs(i) = -(gr.value.g[rows[i]] / scale + 2.0 * kInterior);
    }
    if (req.speed) {
      a.row(m - 1) = gr.dspeed.cwiseProduct(w).transpose();
      rhs(m - 1) = *req.speed - gr.value.speed;
    }
    // Levenberg–Marquardt: the rows are many, near-dependent and possibly inconsistent, so the
    // plain least-squares step can be huge; damping grows until the largest violation drops.
    const MatrixX normal = a.transpose() * a;
    const VectorX g = a.transpose() * rhs;
    const double before = infeasibility(cache, p, req);
    const double base = normal.trace() / static_cast<double>(p.size());
    bool improved = false;
    for (double mu = 1e-10; mu < 1.0 && !improved; mu *= 100.0) {
      const MatrixX damped = normal + mu * base * MatrixX::Identity(p.size(), p.size());
      const VectorX u = damped.ldlt().solve(g);
      const GaitParameters trial = (p + w.cwiseProduct(u)).cwiseMax(vars.lower).cwiseMin(vars.upper);
      if (infeasibility(cache, trial, req) < before) {
        p = trial;
        improved = true;
      }
    }
    if (!improved) break;
  }
  return p;
}

// The full problem from a computable point, with restarts from the last point.
GaitParameters solveFullProblem(GaitEvaluationCache& cache, GaitParameters p,
                                const OptimizationRequest& req, std::ostream* log,
                                OptimizationResult& r, NlpStatus& status) {
  // Objective of order one at the start, so the solver's tolerances are relative.
  const double scale = std::max(1.0, std::abs(criterionValue(cache.values(p), req.criterion)));
  // A quasi-Newton model built across the kinks of the semi-infinite constraints can stall
  // the solver slightly infeasible; a restart from its point rebuilds the model.
  SolverSettings settings = req.solver;
  for (int attempt = 0; attempt <= req.solver.max_restarts; ++attempt) {
    const std::string label = attempt == 0 ? "full" : "full restart " + std::to_string(attempt);
    const NlpSolution sol =
        solveStage(cache, p, 5, kInterior, 0.0, settings, label, log, r, [&](NlpProblem& problem) {
          problem.addCost(makeCriterionCost(cache, req.criterion, scale));
          if (req.speed) problem.addConstraints(makeSpeedConstraint(cache, *req.speed));
        });
    // An NLopt run that broke down on undefined trial points restarts with Ipopt, which
    // refuses them natively (with the exchange method, measured faster for Ipopt).
    if (sol.status == NlpStatus::Failed && settings.backend != Backend::Ipopt) {
      settings.backend = Backend::Ipopt;
      settings.constraint_exchange = true;
    }
    if (!cache.values(sol.x).motion_computed) continue;  // restart from the last point
    status = sol.status;
    const GaitParameters start = p;
    p = sol.x;
    // SLSQP may stop on its objective tolerance a little outside (measured up to ~1e-5 scaled):
    // a restoration step to the nearest feasible point costs O(violation) in the criterion.
    if (status == NlpStatus::Solved && !meetsAll(req, cache.values(p))) p = restore(cache, p, req);
    if (status == NlpStatus::Solved && meetsAll(req, cache.values(p))) break;
    // A restart from the same point repeats the same run (measured: SLSQP returning its start
    // after new points between nodes).
    if (p == start) break;
  }
  return p;
}

// The maxima that are not (nearly) a grid node or an extra point already: a duplicate row would
// make the NLP degenerate.
std::vector<double> newPoints(const std::vector<double>& maxima, const ChebyshevGrid& grid,
                              const std::vector<double>& extra) {
  std::vector<double> added;
  const auto near = [](double s, const auto& set) {
    for (double x : set)
      if (std::abs(x - s) < kMinPointSpacing) return true;
    return false;
  };
  for (double s : maxima)
    if (!near(s, grid.nodes()) && !near(s, extra) && !near(s, added)) added.push_back(s);
  return added;
}

// Adds the near-active local maxima between nodes as extra constraint points when one of them
// is violated; false if none is or no new point was found.
bool addBetweenNodesPoints(const GaitEvaluator& ev, const GaitParameters& p, GaitOptions& o,
                           std::ostream* log) {
  BetweenNodesCheck b = checkBetweenNodes(ev, p, -kNearActive);
  if (!(b.worst_scaled > kBetweenNodesThreshold)) return false;
  b.ss_maxima = newPoints(b.ss_maxima, ev.ssGrid(), o.ss_extra_points);
  b.ds_maxima = newPoints(b.ds_maxima, ev.dsGrid(), o.ds_extra_points);
  if (b.ss_maxima.empty() && b.ds_maxima.empty()) return false;
  o.ss_extra_points.insert(o.ss_extra_points.end(), b.ss_maxima.begin(), b.ss_maxima.end());
  o.ds_extra_points.insert(o.ds_extra_points.end(), b.ds_maxima.begin(), b.ds_maxima.end());
  if (log)
    *log << "[between nodes] worst " << b.worst_scaled << " (scaled, "
         << ev.layout()[b.worst_group].name << "): +" << b.ss_maxima.size() << " SS, +"
         << b.ds_maxima.size() << " DS constraint points (s =";
  if (log) {
    for (double s : b.ss_maxima) *log << " SS " << s;
    for (double s : b.ds_maxima) *log << " DS " << s;
    *log << ")\n";
  }
  return true;
}

}  // namespace

OptimizationResult optimizeGait(const GaitEvaluator& ev, const OptimizationRequest& req,
                                std::ostream* log) {
  const auto t0 = std::chrono::steady_clock::now();
  OptimizationResult r;
  GaitParameters p = gaitVariables(ev.model(), req.initial, ev.options().parameterisation).initial;
  NlpStatus status = NlpStatus::Failed;
  GaitOptions options = ev.options();
  // C_Γ needs no kink splitting (its integrand is smooth): 10× cheaper evaluations.
  options.split_criteria_kinks = req.criterion != Criterion::Torque;
  for (int round = 0; round <= kMaxBetweenNodesRounds; ++round) {
    // Each round solves with the constraint points found between nodes so far.
    const GaitEvaluator work(ev.model().robot, options, ev.model().options);
    GaitEvaluationCache cache(work, req.solver.gradients);
    if (round == 0 && req.solver.hierarchy == HierarchyStrategy::Staged)
      p = repairLowerLevels(cache, p, req, log, r);
    if (round > 0) p = restore(cache, p, req);
    const bool computable = cache.values(p).motion_computed;
    if (computable) p = solveFullProblem(cache, p, req, log, r, status);
    r.function_evaluations += cache.valueEvaluations();
    r.gradient_evaluations += cache.gradientEvaluations();
    // A re-solve that stalls at a point meeting every node and extra point still gets the next
    // exchange round (its new points and restoration can unblock it).
    if (!computable || (status != NlpStatus::Solved && round == 0) ||
        !meetsAll(req, cache.values(p)) || !addBetweenNodesPoints(ev, p, options, log))
      break;
  }
  r.parameters = p;
  r.evaluation = ev.evaluate(p);
  classify(ev, req, status, r);
  r.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace gaitopt
