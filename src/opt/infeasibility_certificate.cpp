#include "gaitopt/opt/infeasibility_certificate.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <Eigen/QR>

#include "gaitopt/gait/feasibility.hpp"
#include "gaitopt/math/nonnegative_least_squares.hpp"
#include "gaitopt/opt/evaluation_cache.hpp"
#include "gaitopt/opt/gait_problem.hpp"
#include "gaitopt/opt/nlp_solver.hpp"

namespace gaitopt {
namespace {

// Levels 0–4 are held this far inside (scaled), as in the optimiser's full stage: the
// evaluator fails them at g > 0.
constexpr double kInterior = 1e-6;
// The elastic variable's lower bound: once every row is met the question is answered (going
// inside them measured hundreds of SLSQP iterations more).
constexpr double kLowestViolation = 0.0;
constexpr double kMaxViolation = 1e3;
constexpr int kMaxElasticSolves = 4;

// A constraint set of the gait parameters (the first n variables) minus `weight` times the
// elastic variable (the last one): g(p) − weight · s.
class Elastic : public ConstraintSet {
 public:
  Elastic(std::unique_ptr<ConstraintSet> inner, int n, double weight)
      : inner_(std::move(inner)), n_(n), weight_(weight) {}
  std::string name() const override { return inner_->name(); }
  int size() const override { return inner_->size(); }
  void bounds(Eigen::Ref<VectorX> lower, Eigen::Ref<VectorX> upper) const override {
    inner_->bounds(lower, upper);
  }
  bool values(const VectorX& x, Eigen::Ref<VectorX> g) override {
    if (!inner_->values(x.head(n_), g)) return false;
    g.array() -= weight_ * x(n_);
    return true;
  }
  bool jacobian(const VectorX& x, Eigen::Ref<MatrixX> jac) override {
    if (!inner_->jacobian(x.head(n_), jac.leftCols(n_))) return false;
    jac.col(n_).setConstant(-weight_);
    return true;
  }

 private:
  std::unique_ptr<ConstraintSet> inner_;
  int n_;
  double weight_;
};

// The elastic variable itself.
class ElasticCost : public CostTerm {
 public:
  explicit ElasticCost(int n) : n_(n) {}
  std::string name() const override { return "violation"; }
  bool value(const VectorX& x, double& f) override {
    f = x(n_);
    return true;
  }
  bool gradient(const VectorX&, Eigen::Ref<VectorX> grad) override {
    grad.setZero();
    grad(n_) = 1.0;
    return true;
  }

 private:
  int n_;
};

std::vector<int> levelFiveEntries(const ConstraintLayout& layout) {
  std::vector<int> out;
  for (int k = 0; k < layout.size(); ++k)
    if (layout.levelOf(k) == 5) out.push_back(k);
  return out;
}

// The elastic problem's level-5 rows: the layout entries `entries` of `cache`'s evaluator, at
// its nodes or also between them. With the verdict's finer evaluator (at its nodes) they are
// the rows the one verdict checks between the nodes.
struct LevelFive {
  GaitEvaluationCache* cache;
  std::vector<int> entries;
  BetweenNodes between;
  std::unique_ptr<ConstraintSet> rows() const {
    return makeHierarchyConstraints(*cache, entries, kInterior, 0.0, between);
  }
};

// The actuated joints in the order of Γ* and of the joint-limit angles (δ1 … δ4).
constexpr const char* kJointNames[4] = {"knee 1", "hip 1", "hip 2", "knee 2"};

// "knee 2 upper", "foot 2 +R_x", … : which row of a node's block `sub` is.
std::string subRowName(int group, int sub) {
  switch (group) {
    case kTorqueSS: case kTorqueDS: case kJointLimitsSS: case kJointLimitsDS:
      return std::string(" ") + kJointNames[sub / 2] + (sub % 2 == 0 ? " upper" : " lower");
    case kFrictionConeSS: case kFrictionConeDS:
      return " foot " + std::to_string(sub / 2 + 1) + (sub % 2 == 0 ? " +R_x" : " -R_x");
    case kNormalForceDS: return " foot " + std::to_string(sub + 1);
    default: return "";
  }
}

// Rows within this (scaled) of their bound count as active at the elastic optimum.
constexpr double kActiveTol = 1e-4;

// The active tolerance at a point whose elastic variable is s: at most half of s, so that a
// row met exactly (g = 0, e.g. a friction cone held by the DS force split's clamp, whose
// gradient vanishes) is not taken as one at s* when s* is small.
double activeTolerance(double s) { return std::min(kActiveTol, 0.5 * std::max(s, 0.0)); }

// A least-squares multiplier vector with a larger relative stationarity residual is no
// certificate.
constexpr double kStationarityTol = 1e-3;

// The multipliers λ ≥ 0 of the rows within `tol` of their bound at x (the equality rows' of
// either sign), by non-negative least squares on ∇f + Jᵀλ + μ = 0 (the other rows' zero; μ
// those of the variables at a bound), each variable scaled by its bound range; false when x is
// not a first-order point (relative residual above kStationarityTol).
bool activeMultipliers(NlpProblem& problem, const VectorX& x, double tol, VectorX& lambda) {
  VectorX g, lower, upper, grad;
  MatrixX jac;
  if (!problem.constraints(x, g) || !problem.constraintJacobian(x, jac) ||
      !problem.costGradient(x, grad))
    return false;
  problem.constraintBounds(lower, upper);
  const VariableSet& v = problem.variables();
  const VectorX D = (v.upper - v.lower).cwiseMin(1.0).cwiseMax(1e-3);
  // Columns: each active row, and the negated equality rows (a free multiplier λ = λ⁺ − λ⁻).
  std::vector<std::pair<int, double>> columns;
  for (int i = 0; i < g.size(); ++i) {
    if (lower(i) == upper(i)) columns.push_back({i, -1.0});
    if (lower(i) == upper(i) || g(i) >= upper(i) - tol) columns.push_back({i, 1.0});
  }
  // And the variables at a bound (their multipliers are not reported).
  std::vector<std::pair<int, double>> bounds;
  for (int j = 0; j < x.size(); ++j) {
    if (x(j) <= v.lower(j) + tol * D(j)) bounds.push_back({j, -1.0});
    if (x(j) >= v.upper(j) - tol * D(j)) bounds.push_back({j, 1.0});
  }
  MatrixX A = MatrixX::Zero(x.size(), columns.size() + bounds.size());
  for (std::size_t j = 0; j < columns.size(); ++j)
    A.col(j) = columns[j].second * jac.row(columns[j].first).transpose().cwiseProduct(D);
  for (std::size_t j = 0; j < bounds.size(); ++j)
    A(bounds[j].first, columns.size() + j) = bounds[j].second * D(bounds[j].first);
  const VectorX gf = grad.cwiseProduct(D);
  const NnlsResult nnls = solveNonnegativeLeastSquares(A, -gf);
  lambda = VectorX::Zero(g.size());
  for (std::size_t j = 0; j < columns.size(); ++j)
    lambda(columns[j].first) += columns[j].second * nnls.x(j);
  return nnls.residual <= kStationarityTol * gf.norm();
}

}  // namespace

int constraintGroupOf(const ConstraintLayout& layout, int entry) {
  for (int id = 0; id < kNumConstraintGroups; ++id)
    if (entry >= layout[id].offset && entry < layout[id].offset + layout[id].count) return id;
  return -1;
}

std::string constraintRowName(const ConstraintLayout& layout, int entry) {
  const int id = constraintGroupOf(layout, entry);
  if (id < 0) return "entry " + std::to_string(entry);
  const ConstraintGroup& g = layout[id];
  if (g.phase == ConstraintPhase::None) return g.name;
  const int node = (entry - g.offset) / g.per_point + g.first_point;
  return g.name + subRowName(id, (entry - g.offset) % g.per_point) + " at " +
         (g.phase == ConstraintPhase::SingleSupport ? "SS" : "DS") + " node " +
         std::to_string(node);
}

namespace {

// The entry of `layout` whose interval holds entry `k` of `fine`, the same layout on a grid
// kBetweenNodesRefinement times finer: same group and sub-row, node ⌊j / refinement⌋ (the
// Chebyshev–Lobatto grids are nested), within the group's nodes. Phase-less entries map to
// themselves.
int coarseEntry(const ConstraintLayout& layout, const ConstraintLayout& fine, int k) {
  const int id = constraintGroupOf(fine, k);
  const ConstraintGroup& f = fine[id];
  const ConstraintGroup& g = layout[id];
  if (g.phase == ConstraintPhase::None) return g.offset + (k - f.offset);
  const int node = (k - f.offset) / f.per_point + f.first_point;
  const int last = g.first_point + g.count / g.per_point - 1;
  const int coarse = std::min(std::max(node / kBetweenNodesRefinement, g.first_point), last);
  return g.offset + (coarse - g.first_point) * g.per_point + (k - f.offset) % f.per_point;
}

// The elastic problem over (p, s) started at x0 = (p0, s0): levels 0–4 of `cache`'s
// evaluator (between the nodes as `between`), the rows of `level5`, the speed.
std::unique_ptr<NlpProblem> elasticProblem(GaitEvaluationCache& cache, const VectorX& x0,
                                           const LevelFive& level5,
                                           const std::optional<double>& speed,
                                           BetweenNodes between) {
  const GaitEvaluator& ev = cache.evaluator();
  const int n = static_cast<int>(x0.size()) - 1;
  const VariableSet gait =
      gaitVariables(ev.model(), GaitParameters(x0.head(n)), ev.options().parameterisation);
  VariableSet vars;
  vars.names = gait.names;
  vars.names.push_back("violation");
  vars.lower.resize(n + 1);
  vars.upper.resize(n + 1);
  vars.initial.resize(n + 1);
  vars.lower << gait.lower, kLowestViolation;
  vars.upper << gait.upper, kMaxViolation;
  vars.initial << gait.initial, x0(n);
  auto problem = std::make_unique<NlpProblem>(vars);
  problem->addCost(std::make_unique<ElasticCost>(n));
  problem->addConstraints(std::make_unique<Elastic>(
      makeHierarchyConstraints(cache, hierarchyEntries(ev.layout(), 4), kInterior, 0.0, between),
      n, 0.0));
  problem->addConstraints(std::make_unique<Elastic>(level5.rows(), n, 1.0));
  if (speed)
    problem->addConstraints(
        std::make_unique<Elastic>(makeSpeedConstraint(cache, *speed), n, 0.0));
  return problem;
}

// One elastic problem solved from `start`: the point, the multipliers of its rows (when
// first-order), and the worst scaled level-5 row there.
struct ElasticSolve {
  VectorX x, lambda, rows;
  bool stationary = false;
  int iterations = 0;
  double worst = kMaxViolation;
};

ElasticSolve solveElastic(GaitEvaluationCache& cache, const GaitParameters& start,
                          const LevelFive& level5, const std::optional<double>& speed,
                          BetweenNodes between, int max_iter) {
  const int n = start.size();
  ElasticSolve out;
  // Start with s at the start's worst row (at least its lower bound), so that every elastic
  // row holds there.
  const std::unique_ptr<ConstraintSet> rows = level5.rows();
  out.rows.resize(rows->size());
  const bool started = rows->values(start, out.rows) && out.rows.size() > 0;
  const double s0 = started ? std::max(out.rows.maxCoeff(), 0.0) : 1.0;
  out.x.resize(n + 1);
  out.x << start, s0;
  // SLSQP: it measured reliable on this problem's ~1200 rows, where Ipopt's interior point
  // stalled with every multiplier near 1/rows. Its quasi-Newton model can stop short of a
  // first-order point: restarted from its own end (a fresh model) while that lowers s.
  NlpSettings settings;
  settings.max_iter = max_iter;
  settings.tol = 1e-10;
  settings.print_every = 0;
  for (int solve = 0; solve < kMaxElasticSolves && !out.stationary; ++solve) {
    const std::unique_ptr<NlpProblem> problem =
        elasticProblem(cache, out.x, level5, speed, between);
    const NlpSolution sol = solveWithNlopt(*problem, settings, NloptMethod::Slsqp);
    out.iterations += sol.iterations;
    const bool computed = rows->values(sol.x.head(n), out.rows);
    out.worst = computed && out.rows.size() > 0 ? out.rows.maxCoeff() : kMaxViolation;
    // SLSQP can end with s below the rows it bounds (measured: s = 0 with a row at +1.03),
    // where any row met exactly would be active and the bound s ≥ 0 would absorb ∂/∂s. The
    // elastic problem's value at p is its worst row: the multipliers are taken there.
    const double s = std::max(out.worst, kLowestViolation);
    const bool lower = s < out.x(n) - kActiveTol;
    out.x << sol.x.head(n), s;
    out.stationary = computed && sol.status == NlpStatus::Solved &&
                     activeMultipliers(*problem, out.x, activeTolerance(s), out.lambda);
    if (!lower && solve > 0) break;
  }
  return out;
}

}  // namespace

InfeasibilityCertificate minimiseViolation(const GaitEvaluator& ev, const GaitParameters& start,
                                           const std::optional<double>& speed, int max_iter) {
  const auto t0 = std::chrono::steady_clock::now();
  // Constraints only: the criteria's finer SS grid is not needed.
  const GaitEvaluator solving = ev.withCriteriaRefinement(1);
  GaitEvaluationCache cache(solving);
  const ConstraintLayout& layout = ev.layout();
  const int n = start.size();
  const auto verdict = [&](const GaitParameters& p) {
    return feasibilityVerdict(ev, p, ev.evaluate(p), speed).feasible;
  };
  const auto blocks = [](const ElasticSolve& e) {
    return e.stationary && e.worst > kFeasibilityTolerance;
  };

  // At the nodes first: smooth rows (no maxima with kinks, where SLSQP measured stuck), and
  // a step that cannot meet its rows at the nodes cannot meet them between either. When they
  // can be met, the rows between the nodes too, from there: a feasible start, or the evidence
  // between the nodes.
  LevelFive level5{&cache, levelFiveEntries(layout), BetweenNodes::None};
  ElasticSolve e = solveElastic(cache, start, level5, speed, BetweenNodes::None, max_iter);
  int iterations = e.iterations;
  if (!blocks(e)) {
    level5.between = BetweenNodes::Both;
    e = solveElastic(cache, GaitParameters(e.x.head(n)), level5, speed, BetweenNodes::Both,
                     max_iter);
    iterations += e.iterations;
  }
  bool feasible = verdict(GaitParameters(e.x.head(n)));
  // The interpolant's maxima can miss a feature narrower than the node spacing (measured:
  // the Coulomb torque's sign change, 28 N·m within 3 % of the SS, left torque_envelope_ss
  // met on every row and 4.1 N·m over on the verdict's grid): then the rows of the verdict's
  // own 10× finer grid, from there, so that s* > 0 is evidence against the verdict itself.
  std::unique_ptr<GaitEvaluator> fine;
  std::unique_ptr<GaitEvaluationCache> fine_cache;
  const bool finer = !feasible && !blocks(e);
  if (finer) {
    fine = std::make_unique<GaitEvaluator>(betweenNodesEvaluator(solving));
    fine_cache = std::make_unique<GaitEvaluationCache>(*fine);
    level5 = LevelFive{fine_cache.get(), levelFiveEntries(fine->layout()), BetweenNodes::None};
    e = solveElastic(cache, GaitParameters(e.x.head(n)), level5, speed, BetweenNodes::Both,
                     max_iter);
    iterations += e.iterations;
    feasible = verdict(GaitParameters(e.x.head(n)));
  }
  const ConstraintLayout& rows = level5.cache->evaluator().layout();

  InfeasibilityCertificate c;
  c.x = GaitParameters(e.x.head(n));
  c.iterations = iterations;
  c.feasible = feasible;
  c.converged = e.stationary && !c.feasible;
  c.min_violation = e.worst;
  const int first = static_cast<int>(hierarchyEntries(layout, 4).size());
  // Rows that can all be met block nothing. A row of the finer grid is reported as the row
  // of the interval of ev's grid holding it (the multipliers of its rows summed, its largest
  // value).
  const bool blocked = c.converged && c.min_violation > kFeasibilityTolerance;
  std::vector<BlockingConstraint> found;
  for (int i = 0; blocked && i < static_cast<int>(level5.entries.size()); ++i) {
    const double lambda = e.lambda(first + i);
    if (lambda <= 0.0) continue;
    const int k = level5.entries[i];
    const double value = e.rows(i) * constraintScale(rows, ev.model(), k);
    const int entry = finer ? coarseEntry(layout, rows, k) : k;
    auto same = std::find_if(found.begin(), found.end(),
                             [&](const BlockingConstraint& b) { return b.entry == entry; });
    if (same == found.end()) {
      BlockingConstraint b;
      b.entry = entry;
      b.name = constraintRowName(layout, entry) +
               (level5.between == BetweenNodes::None && !finer ? "" : " (between nodes)");
      b.unit = layout[constraintGroupOf(layout, entry)].unit;
      b.value = value;
      found.push_back(b);
      same = found.end() - 1;
    }
    same->multiplier += lambda;
    same->value = std::max(same->value, value);
  }
  for (const BlockingConstraint& b : found)
    if (b.multiplier >= kBlockingMultiplier) c.blocking.push_back(b);
  std::sort(c.blocking.begin(), c.blocking.end(),
            [](const BlockingConstraint& a, const BlockingConstraint& b) {
              return a.multiplier > b.multiplier;
            });
  c.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return c;
}

}  // namespace gaitopt
