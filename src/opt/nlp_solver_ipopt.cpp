// Ipopt TNLP adapter: translates NlpProblem calls; an undefined evaluation returns false, which
// makes Ipopt shorten its step (or enter restoration) instead of crashing.
#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <vector>

#include "gaitopt/opt/hessian_modification.hpp"
#include "gaitopt/opt/nlp_solver.hpp"

namespace gaitopt {
namespace {

using Ipopt::Index;
using Ipopt::Number;

// A constraint within this distance of a bound (scaled units) counts as active when the exact
// Hessian is made positive-definite on the active constraints' null space.
constexpr double kActiveDistance = 1e-3;
// Smallest eigenvalue of the modified reduced Hessian, relative to its largest |eigenvalue|.
constexpr double kMinRelativeCurvature = 1e-6;

class TnlpAdapter : public Ipopt::TNLP {
 public:
  TnlpAdapter(NlpProblem& p, const NlpSettings& s)
      : problem_(p), settings_(s), bfgs_(p.variables().size()) {}

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac, Index& nnz_h,
                    IndexStyleEnum& style) override {
    n = problem_.variables().size();
    m = problem_.numConstraints();
    nnz_jac = n * m;  // dense: every constraint depends on every gait parameter
    nnz_h = settings_.hessian == HessianMode::LimitedMemory ? 0 : n * (n + 1) / 2;
    style = C_STYLE;
    return true;
  }
  bool get_bounds_info(Index n, Number* xl, Number* xu, Index m, Number* gl,
                       Number* gu) override {
    Eigen::Map<VectorX>(xl, n) = problem_.variables().lower;
    Eigen::Map<VectorX>(xu, n) = problem_.variables().upper;
    VectorX lo, hi;
    problem_.constraintBounds(lo, hi);
    Eigen::Map<VectorX>(gl, m) = lo;
    Eigen::Map<VectorX>(gu, m) = hi;
    return true;
  }
  bool get_starting_point(Index n, bool, Number* x, bool init_z, Number* z_l, Number* z_u,
                          Index m, bool init_lambda, Number* lambda) override {
    Eigen::Map<VectorX>(x, n) = problem_.variables().initial;
    const NlpMultipliers& w = settings_.warm_start;
    if (init_z) {
      Eigen::Map<VectorX>(z_l, n) = w.z_lower;
      Eigen::Map<VectorX>(z_u, n) = w.z_upper;
    }
    if (init_lambda) Eigen::Map<VectorX>(lambda, m) = w.lambda;
    return true;
  }
  bool eval_f(Index n, const Number* x, bool, Number& f) override {
    evaluated_x_ = Eigen::Map<const VectorX>(x, n);
    return problem_.cost(evaluated_x_, f);
  }
  bool eval_grad_f(Index n, const Number* x, bool, Number* grad) override {
    VectorX g;
    if (!problem_.costGradient(VectorX(Eigen::Map<const VectorX>(x, n)), g)) return false;
    Eigen::Map<VectorX>(grad, n) = g;
    return true;
  }
  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    VectorX v;
    if (!problem_.constraints(VectorX(Eigen::Map<const VectorX>(x, n)), v)) return false;
    Eigen::Map<VectorX>(g, m) = v;
    return true;
  }
  bool eval_jac_g(Index n, const Number* x, bool, Index m, Index, Index* rows, Index* cols,
                  Number* values) override {
    if (values == nullptr) {
      for (Index i = 0, k = 0; i < m; ++i)
        for (Index j = 0; j < n; ++j, ++k) {
          rows[k] = i;
          cols[k] = j;
        }
      return true;
    }
    MatrixX jac;
    if (!problem_.constraintJacobian(VectorX(Eigen::Map<const VectorX>(x, n)), jac)) return false;
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(values, m,
                                                                                       n) = jac;
    return true;
  }
  bool eval_h(Index n, const Number* x, bool, Number sigma, Index m, const Number* lambda, bool,
              Index, Index* rows, Index* cols, Number* values) override {
    if (values == nullptr) {
      for (Index i = 0, k = 0; i < n; ++i)
        for (Index j = 0; j <= i; ++j, ++k) {
          rows[k] = i;
          cols[k] = j;
        }
      return true;
    }
    const VectorX xv = Eigen::Map<const VectorX>(x, n);
    const VectorX lv = Eigen::Map<const VectorX>(lambda, m);
    MatrixX hess;
    const HessianMode mode = settings_.hessian;
    const bool ok = mode == HessianMode::GaussNewton ? gaussNewtonHessian(xv, sigma, lv, hess)
                    : mode == HessianMode::DenseBfgs ? bfgsHessian(xv, sigma, lv, hess)
                                                     : exactHessian(xv, sigma, lv, hess);
    if (!ok) return false;
    for (Index i = 0, k = 0; i < n; ++i)
      for (Index j = 0; j <= i; ++j, ++k) values[k] = hess(i, j);
    return true;
  }
  void finalize_solution(Ipopt::SolverReturn status, Index n, const Number* x, const Number* z_l,
                         const Number* z_u, Index m, const Number*, const Number* lambda,
                         Number obj, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    solution_.x = Eigen::Map<const VectorX>(x, n);
    solution_.multipliers = {Eigen::Map<const VectorX>(z_l, n), Eigen::Map<const VectorX>(z_u, n),
                             Eigen::Map<const VectorX>(lambda, m)};
    solution_.objective = obj;
    solution_.status = toStatus(status);
  }
  bool intermediate_callback(Ipopt::AlgorithmMode mode, Index iter, Number obj, Number inf_pr,
                             Number inf_du, Number, Number, Number, Number, Number, Index,
                             const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
    solution_.iterations = iter;
    if (settings_.on_iteration && evaluated_x_.size() > 0) settings_.on_iteration(evaluated_x_, iter);
    if (settings_.log && settings_.print_every > 0 && iter % settings_.print_every == 0) {
      char line[160];
      std::snprintf(line, sizeof line, "[%s] iter %4d  objective %.8e  violation %.3e  dual %.3e%s\n",
                    settings_.label.c_str(), static_cast<int>(iter), obj, inf_pr, inf_du,
                    mode == Ipopt::RestorationPhaseMode ? "  (restoration)" : "");
      *settings_.log << line << std::flush;
    }
    return true;
  }
  const NlpSolution& solution() const { return solution_; }

 private:
  // BFGS pair from the previous Hessian point, both gradients taken with today's multipliers;
  // `known` (σ times the cost's Hessian at x, or empty) is the part of the Lagrangian's
  // curvature given exactly: the pair's y leaves out its share, and it is added to the model.
  bool bfgsHessian(const VectorX& x, double sigma, const VectorX& lambda, MatrixX& hess,
                   const MatrixX& known = MatrixX()) {
    VectorX grad_f;
    MatrixX jac;
    if (!problem_.costGradient(x, grad_f) || !problem_.constraintJacobian(x, jac)) return false;
    if (last_x_.size() > 0 && last_x_ != x) {
      const VectorX s = x - last_x_;
      VectorX y = sigma * (grad_f - last_grad_f_) + (jac - last_jac_).transpose() * lambda;
      if (known.size() > 0) y -= known * s;
      bfgs_.update(s, y);
    }
    last_x_ = x;
    last_grad_f_ = grad_f;
    last_jac_ = jac;
    hess = bfgs_.matrix();
    if (known.size() > 0) hess += known;
    return true;
  }
  bool gaussNewtonHessian(const VectorX& x, double sigma, const VectorX& lambda, MatrixX& hess) {
    if (!problem_.hasCostHessian()) return bfgsHessian(x, sigma, lambda, hess);
    MatrixX known;
    if (!problem_.costHessian(x, known)) return false;
    // The Gauss–Newton part alone (no model of the rest) measured worse: Ipopt failed on the
    // default problem, the constraints' curvature matters at its active rows.
    return bfgsHessian(x, sigma, lambda, hess, sigma * known);
  }
  bool exactHessian(const VectorX& x, double sigma, const VectorX& lambda, MatrixX& hess) {
    if (!problem_.lagrangianHessian(x, sigma, lambda, hess)) return false;
    if (settings_.hessian != HessianMode::Exact) return true;
    VectorX g, lo, hi;
    MatrixX jac;
    if (!problem_.constraints(x, g) || !problem_.constraintJacobian(x, jac)) return false;
    problem_.constraintBounds(lo, hi);
    std::vector<int> active;
    for (int i = 0; i < g.size(); ++i)
      if (g(i) - lo(i) <= kActiveDistance || hi(i) - g(i) <= kActiveDistance) active.push_back(i);
    const double largest = std::max(1e-12, hess.cwiseAbs().maxCoeff());
    hess = positiveOnNullSpace(hess, jac(active, Eigen::all), kMinRelativeCurvature * largest);
    return true;
  }
  static NlpStatus toStatus(Ipopt::SolverReturn s) {
    switch (s) {
      case Ipopt::SUCCESS:
      case Ipopt::STOP_AT_ACCEPTABLE_POINT: return NlpStatus::Solved;
      case Ipopt::LOCAL_INFEASIBILITY: return NlpStatus::Infeasible;
      case Ipopt::MAXITER_EXCEEDED:
      case Ipopt::CPUTIME_EXCEEDED: return NlpStatus::MaxIterations;
      default: return NlpStatus::Failed;
    }
  }
  NlpProblem& problem_;
  const NlpSettings& settings_;
  NlpSolution solution_;
  DampedBfgs bfgs_;
  VectorX evaluated_x_;  // the last point Ipopt asked a cost of: the progress lines' iterate
  VectorX last_x_, last_grad_f_;  // the previous Hessian point (BFGS pair)
  MatrixX last_jac_;
};

// Integer-looking values as integers, other numbers as reals, the rest as strings; the key of
// the first option Ipopt rejects, or "".
std::string applyIpoptOptions(Ipopt::OptionsList& o,
                              const std::vector<std::pair<std::string, std::string>>& options) {
  for (const auto& [key, value] : options) {
    char* end = nullptr;
    const long integer = std::strtol(value.c_str(), &end, 10);
    bool ok;
    if (!value.empty() && *end == '\0') {
      ok = o.SetIntegerValue(key, static_cast<Index>(integer));
    } else {
      const double real = std::strtod(value.c_str(), &end);
      ok = (!value.empty() && *end == '\0') ? o.SetNumericValue(key, real)
                                             : o.SetStringValue(key, value);
    }
    if (!ok) return key;
  }
  return "";
}

// min (x - 1)^2 on one bounded variable: the smallest problem that makes Ipopt factorise a
// matrix, i.e. load its linear solver.
class ProbeProblem : public Ipopt::TNLP {
 public:
  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac, Index& nnz_h,
                    IndexStyleEnum& style) override {
    n = 1;
    m = 0;
    nnz_jac = 0;
    nnz_h = 1;
    style = C_STYLE;
    return true;
  }
  bool get_bounds_info(Index, Number* xl, Number* xu, Index, Number*, Number*) override {
    xl[0] = -10.0;
    xu[0] = 10.0;
    return true;
  }
  bool get_starting_point(Index, bool, Number* x, bool, Number*, Number*, Index, bool,
                          Number*) override {
    x[0] = 0.0;
    return true;
  }
  bool eval_f(Index, const Number* x, bool, Number& f) override {
    f = (x[0] - 1.0) * (x[0] - 1.0);
    return true;
  }
  bool eval_grad_f(Index, const Number* x, bool, Number* g) override {
    g[0] = 2.0 * (x[0] - 1.0);
    return true;
  }
  bool eval_g(Index, const Number*, bool, Index, Number*) override { return true; }
  bool eval_jac_g(Index, const Number*, bool, Index, Index, Index*, Index*, Number*) override {
    return true;
  }
  bool eval_h(Index, const Number*, bool, Number factor, Index, const Number*, bool, Index,
              Index* rows, Index* cols, Number* values) override {
    if (values == nullptr) {
      rows[0] = 0;
      cols[0] = 0;
    } else {
      values[0] = 2.0 * factor;
    }
    return true;
  }
  void finalize_solution(Ipopt::SolverReturn, Index, const Number*, const Number*, const Number*,
                         Index, const Number*, const Number*, Number, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {}
};

// One Ipopt solve at a time in the process: Ipopt with the sequential MUMPS crashes when two
// solves run at once (measured: four threads, tests/opt/test_ipopt_warm_start.cpp), while a
// sweep's SLSQP chains run on threads and may each call Ipopt (projections, the switch after a
// breakdown).
std::mutex& oneSolveAtATime() {
  static std::mutex m;
  return m;
}

}  // namespace

bool ipoptLinearSolverAvailable(const std::string& name) {
  const std::lock_guard<std::mutex> lock(oneSolveAtATime());
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Jnlst()->DeleteAllJournals();  // the probe must stay silent, whatever Ipopt reports
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetStringValue("sb", "yes");
  if (!app->Options()->SetStringValue("linear_solver", name)) return false;
  if (app->Initialize() != Ipopt::Solve_Succeeded) return false;
  Ipopt::SmartPtr<Ipopt::TNLP> probe = new ProbeProblem();
  return app->OptimizeTNLP(probe) == Ipopt::Solve_Succeeded;
}

std::string rejectedIpoptOption(const std::vector<std::pair<std::string, std::string>>& options) {
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetIntegerValue("print_level", 0);
  app->Jnlst()->DeleteAllJournals();
  return applyIpoptOptions(*app->Options(), options);
}

NlpSolution solveWithIpopt(NlpProblem& problem, const NlpSettings& settings) {
  const std::lock_guard<std::mutex> lock(oneSolveAtATime());
  Ipopt::SmartPtr<TnlpAdapter> nlp = new TnlpAdapter(problem, settings);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  Ipopt::OptionsList& o = *app->Options();
  o.SetIntegerValue("print_level", 0);
  o.SetStringValue("sb", "yes");
  if (settings.hessian == HessianMode::LimitedMemory) {
    o.SetStringValue("hessian_approximation", "limited-memory");
    o.SetStringValue("mu_strategy", "adaptive");
  } else {
    // Tuned on the default problem with the dense Hessians (docs/formats/optimizer-config.md): the
    // monotone barrier update (Fiacco–McCormick) halved the iterations of the adaptive one,
    // which cut μ early and then spent a third of its iterations in restoration. Neighbouring
    // grid entries have nearly equal Jacobian rows, so Ipopt's least-squares initial
    // multipliers reach ~1e10: they start at zero. No early stop at an "acceptable" point.
    o.SetStringValue("mu_strategy", "monotone");
    o.SetNumericValue("constr_mult_init_max", 0.0);
    o.SetIntegerValue("acceptable_iter", 0);
    // The KKT system (every grid entry, a dense Jacobian) costs ~90 % of Ipopt's time, in
    // MUMPS: no residual check and iterative refinement after each solve. Measured on the
    // default problem: same iterations and optimum, 28 % less CPU time (docs/formats/optimizer-config.md).
    o.SetStringValue("fast_step_computation", "yes");
  }
  if (!settings.warm_start.empty()) {
    // Start at the given primal-dual point, not pushed into the interior nor re-initialised:
    // the previous stage's optimum with its active constraints.
    o.SetStringValue("warm_start_init_point", "yes");
    for (const char* key : {"warm_start_bound_push", "warm_start_bound_frac",
                            "warm_start_slack_bound_push", "warm_start_slack_bound_frac",
                            "warm_start_mult_bound_push"})
      o.SetNumericValue(key, 1e-9);
    o.SetNumericValue("mu_init", 1e-6);
  }
  o.SetIntegerValue("max_iter", settings.max_iter);
  o.SetNumericValue("tol", settings.tol);
  o.SetNumericValue("constr_viol_tol", settings.constraint_tol);
  o.SetNumericValue("acceptable_constr_viol_tol", settings.constraint_tol);
  applyIpoptOptions(o, settings.ipopt_options);
  NlpSolution failed;
  failed.x = problem.variables().initial;
  if (app->Initialize() != Ipopt::Solve_Succeeded) {
    failed.message = "Ipopt could not be initialised";
    return failed;
  }
  const Ipopt::ApplicationReturnStatus st = app->OptimizeTNLP(nlp);
  NlpSolution sol = nlp->solution();
  if (sol.x.size() == 0) sol = failed;
  sol.message = "Ipopt return status " + std::to_string(static_cast<int>(st));
  return sol;
}

const char* nlpStatusName(NlpStatus s) {
  switch (s) {
    case NlpStatus::Solved: return "solved";
    case NlpStatus::Infeasible: return "infeasible";
    case NlpStatus::MaxIterations: return "max_iter";
    default: return "failed";
  }
}

}  // namespace gaitopt
