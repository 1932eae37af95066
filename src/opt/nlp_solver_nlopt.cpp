// NLopt adapter. NLopt has no "cannot evaluate" answer: at an undefined step the objective is
// reported as kUndefinedCost and every constraint as violated, so SLSQP's line search on its
// merit function backtracks, the role Ipopt's "cannot evaluate" plays.
#include <algorithm>
#include <array>
#include <nlopt.hpp>
#include <utility>

#include "gaitopt/opt/nlp_solver.hpp"

namespace gaitopt {
namespace {

constexpr double kUndefinedCost = 1e20;
constexpr double kUndefinedViolation = 1e3;

struct NloptContext {
  NloptContext(NlpProblem& p, const NlpSettings& s, VectorX start)
      : problem(p), settings(s), last_x(std::move(start)) {}
  NlpProblem& problem;
  const NlpSettings& settings;
  int evaluations = 0;
  double violation = 0.0;  // largest constraint violation at the last constraint evaluation
  // Each callback's (inequalities, equalities) largest violation and the point it was at:
  // NLopt's SLSQP evaluates the equalities before the inequalities.
  std::array<double, 2> part_violation{0.0, 0.0};
  std::array<VectorX, 2> part_at;
  // The best point seen whose objective and constraints were both evaluated and whose largest
  // violation is within the problem's tolerance (NLopt keeps only points feasible to its own,
  // stricter test, so a run that ends oscillating could otherwise return its start).
  VectorX last_x;  // last point with a defined objective
  VectorX best_x;  // best tolerance-feasible point seen
  double last_f = 0.0, best_f = 0.0;
  bool have_best = false;
  // Records one callback's violation at x; once the objective and every callback are known
  // at the same point, keeps it if it is the best tolerance-feasible one.
  void consider(const VectorX& x, int part, double part_worst, bool has_equalities,
                double tol) {
    part_violation[part] = part_worst;
    part_at[part] = x;
    violation = part_worst;
    const bool complete = !has_equalities || (part_at[0].size() == x.size() &&
                                              part_at[1].size() == x.size() &&
                                              part_at[0] == x && part_at[1] == x);
    if (!complete) return;
    violation = has_equalities ? std::max(part_violation[0], part_violation[1]) : part_worst;
    if (x.size() == last_x.size() && x == last_x && violation <= tol &&
        (!have_best || last_f < best_f)) {
      best_x = x;
      best_f = last_f;
      have_best = true;
    }
  }
};

double objective(unsigned n, const double* x, double* grad, void* data) {
  auto* c = static_cast<NloptContext*>(data);
  const VectorX v = Eigen::Map<const VectorX>(x, n);
  double f = 0.0;
  VectorX g;
  if (!c->problem.cost(v, f) || (grad && !c->problem.costGradient(v, g))) {
    if (grad) Eigen::Map<VectorX>(grad, n).setZero();
    return kUndefinedCost;
  }
  if (grad) Eigen::Map<VectorX>(grad, n) = g;
  ++c->evaluations;
  c->last_x = v;
  c->last_f = f;
  if (c->settings.on_iteration) c->settings.on_iteration(v, c->evaluations);
  if (c->settings.log && c->settings.print_every > 0 && c->evaluations % c->settings.print_every == 0)
    *c->settings.log << "[" << c->settings.label << "] eval " << c->evaluations << "  objective "
                     << f << "  violation " << c->violation << "\n";
  return f;
}

// NLopt wants c(x) ≤ 0 and h(x) = 0: an inequality row gives (g − upper) and, where the lower
// bound is finite, (lower − g); a row with lower = upper (the speed (3.50)) is an equality,
// which SQP handles far better than two opposite inequalities.
struct RowMap {
  std::vector<int> upper_rows, lower_rows, equality_rows;
  VectorX lower, upper;
  std::size_t inequalities() const { return upper_rows.size() + lower_rows.size(); }
};

RowMap rowMap(const NlpProblem& p) {
  RowMap r;
  p.constraintBounds(r.lower, r.upper);
  for (int i = 0; i < r.lower.size(); ++i) {
    if (r.lower(i) == r.upper(i)) {
      r.equality_rows.push_back(i);
      continue;
    }
    if (r.upper(i) < 1e19) r.upper_rows.push_back(i);
    if (r.lower(i) > -1e19) r.lower_rows.push_back(i);
  }
  return r;
}

struct ConstraintContext {
  NloptContext* base;
  RowMap rows;
  bool equalities;  // this callback fills the equality rows
};

void constraints(unsigned, double* result, unsigned n, const double* x, double* grad, void* data) {
  auto* c = static_cast<ConstraintContext*>(data);
  const VectorX v = Eigen::Map<const VectorX>(x, n);
  VectorX g;
  MatrixX jac;
  const std::size_t rows = c->equalities ? c->rows.equality_rows.size() : c->rows.inequalities();
  if (!c->base->problem.constraints(v, g) || (grad && !c->base->problem.constraintJacobian(v, jac))) {
    std::fill(result, result + rows, kUndefinedViolation);
    if (grad) std::fill(grad, grad + rows * n, 0.0);
    return;
  }
  int out = 0;
  const auto put = [&](int i, double sign, double offset) {
    result[out] = sign * (g(i) - offset);
    if (grad)
      for (unsigned j = 0; j < n; ++j) grad[out * n + j] = sign * jac(i, j);
    ++out;
  };
  double worst = 0.0;
  if (c->equalities) {
    for (int i : c->rows.equality_rows) put(i, 1.0, c->rows.upper(i));
    for (int k = 0; k < out; ++k) worst = std::max(worst, std::abs(result[k]));
  } else {
    for (int i : c->rows.upper_rows) put(i, 1.0, c->rows.upper(i));
    for (int i : c->rows.lower_rows) put(i, -1.0, c->rows.lower(i));
    for (int k = 0; k < out; ++k) worst = std::max(worst, result[k]);
  }
  c->base->consider(v, c->equalities ? 1 : 0, worst, !c->rows.equality_rows.empty(),
                    10.0 * c->base->settings.constraint_tol);
}

// Largest violation of the bounds at x (kUndefinedViolation where not computable).
double violationAt(NlpProblem& problem, const RowMap& rows, const VectorX& x) {
  VectorX g;
  if (!problem.constraints(x, g)) return kUndefinedViolation;
  double worst = 0.0;
  for (int i = 0; i < g.size(); ++i)
    worst = std::max({worst, g(i) - rows.upper(i), rows.lower(i) - g(i)});
  return worst;
}

}  // namespace

NlpSolution solveWithNlopt(NlpProblem& problem, const NlpSettings& settings, NloptMethod method) {
  const VariableSet& vars = problem.variables();
  const unsigned n = static_cast<unsigned>(vars.size());
  nlopt::opt opt(method == NloptMethod::Slsqp ? nlopt::LD_SLSQP : nlopt::LN_COBYLA, n);
  NloptContext ctx(problem, settings, vars.initial);
  opt.set_lower_bounds(std::vector<double>(vars.lower.data(), vars.lower.data() + n));
  opt.set_upper_bounds(std::vector<double>(vars.upper.data(), vars.upper.data() + n));
  opt.set_min_objective(objective, &ctx);
  ConstraintContext inequalities{&ctx, rowMap(problem), false};
  ConstraintContext equalities{&ctx, inequalities.rows, true};
  opt.add_inequality_mconstraint(
      constraints, &inequalities,
      std::vector<double>(inequalities.rows.inequalities(), settings.constraint_tol));
  if (!equalities.rows.equality_rows.empty())
    opt.add_equality_mconstraint(
        constraints, &equalities,
        std::vector<double>(equalities.rows.equality_rows.size(), settings.constraint_tol));
  opt.set_ftol_rel(settings.tol);
  opt.set_xtol_rel(settings.tol);
  opt.set_maxeval(method == NloptMethod::Slsqp ? settings.max_iter : 50 * settings.max_iter);
  std::vector<double> x(vars.initial.data(), vars.initial.data() + n);
  NlpSolution sol;
  double f = 0.0;
  try {
    const nlopt::result r = opt.optimize(x, f);
    sol.status = r == nlopt::MAXEVAL_REACHED ? NlpStatus::MaxIterations : NlpStatus::Solved;
    sol.x = Eigen::Map<const VectorX>(x.data(), n);
  } catch (const std::exception& e) {
    // NLopt leaves its best point in x also when it stops on an error (e.g. roundoff-limited).
    sol.status = NlpStatus::Failed;
    sol.x = Eigen::Map<const VectorX>(x.data(), n);
    sol.message = e.what();
  }
  // A better point seen on the way than the one NLopt returns, or a tolerance-feasible one
  // when NLopt, having found none feasible to its stricter test, returns its lowest cost.
  double returned = 0.0;
  if (ctx.have_best &&
      (!problem.cost(sol.x, returned) || ctx.best_f < returned ||
       violationAt(problem, inequalities.rows, sol.x) > 10.0 * settings.constraint_tol)) {
    sol.x = ctx.best_x;
    f = ctx.best_f;
  }
  // SLSQP may end on a refused (undefined) trial point: fall back to the last defined one.
  double check = 0.0;
  if (!problem.cost(sol.x, check)) {
    sol.x = ctx.last_x;
    sol.status = NlpStatus::Failed;
    f = problem.cost(sol.x, check) ? check : f;
  }
  sol.objective = f;
  sol.iterations = ctx.evaluations;
  return sol;
}

}  // namespace gaitopt
