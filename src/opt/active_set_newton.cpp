#include "gaitopt/opt/active_set_newton.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace gaitopt {
namespace {

constexpr int kMaxNewtonSteps = 6;
constexpr int kMaxHalvings = 12;
// Scaled gradient norm below which an active row is taken as not movable.
constexpr double kDegenerateRow = 1e-8;
// Rows met to this (scaled) are solved: Newton converges quadratically from 1e-4.
constexpr double kNewtonResidual = 1e-11;

// The linearised active rows r + J dy = 0 in scaled parameters y = x / D.
struct ActiveSystem {
  MatrixX J;
  VectorX r;
  int inequalities = 0;  // the first rows; the speed, if any, is last
};

// Adds to `active` each computed entry of levels 0–5 within `interior` of its bound or beyond.
void growActiveSet(const GaitEvaluator& ev, const GaitEvaluation<double>& e, double interior,
                   std::vector<int>& active) {
  for (int k : hierarchyEntries(ev.layout(), 5))
    if (e.state[k] != ConstraintState::NotComputed &&
        e.g[k] / constraintScale(ev.layout(), ev.model(), k) > -interior &&
        std::find(active.begin(), active.end(), k) == active.end())
      active.push_back(k);
}

ActiveSystem activeSystem(const GaitEvaluator& ev, const GaitGradient& gr,
                          const std::vector<int>& active, const std::optional<double>& speed,
                          const GaitParameters& D, double interior) {
  ActiveSystem s{MatrixX(active.size() + 1, D.size()), VectorX(active.size() + 1), 0};
  for (int k : active) {
    const double scale = constraintScale(ev.layout(), ev.model(), k);
    s.J.row(s.inequalities) = gr.dg.row(k).cwiseProduct(D.transpose()) / scale;
    // A row that does not move to first order (a friction-cone or force entry identically at
    // its bound where the DS distribution is clamped) would ask for an unbounded step; it
    // stays as it is, and the feasibility check still sees it.
    if (s.J.row(s.inequalities).norm() < kDegenerateRow) continue;
    s.r(s.inequalities++) = gr.value.g[k] / scale + interior;
  }
  int rows = s.inequalities;
  if (speed) {
    s.r(rows) = gr.value.speed - *speed;
    s.J.row(rows++) = gr.dspeed.cwiseProduct(D).transpose();
  }
  s.J.conservativeResize(rows, Eigen::NoChange);
  s.r.conservativeResize(rows);
  return s;
}

bool meets(const GaitEvaluator& ev, const GaitEvaluation<double>& e,
           const std::optional<double>& speed, double tol) {
  if (!e.motion_computed || (speed && std::abs(e.speed - *speed) > tol)) return false;
  for (int k : hierarchyEntries(ev.layout(), 5))
    if (e.state[k] != ConstraintState::NotComputed &&
        e.g[k] / constraintScale(ev.layout(), ev.model(), k) > tol)
      return false;
  return true;
}

// Largest violation of the levels 0–5 (scaled, beyond −interior) and of the speed; infinite
// where the motion cannot be computed.
double violation(GaitEvaluationCache& cache, const GaitParameters& x,
                 const std::optional<double>& speed, double interior) {
  const GaitEvaluator& ev = cache.evaluator();
  const GaitEvaluation<double>& e = cache.values(x);
  if (!e.motion_computed) return std::numeric_limits<double>::infinity();
  double worst = speed ? std::abs(e.speed - *speed) : 0.0;
  for (int k : hierarchyEntries(ev.layout(), 5))
    if (e.state[k] != ConstraintState::NotComputed)
      worst = std::max(worst, e.g[k] / constraintScale(ev.layout(), ev.model(), k) + interior);
  return worst;
}

// Backtracking on the Newton step dx (halved up to kMaxHalvings times) until the largest
// violation decreases: the linearisation holds only near x, and a row with a small gradient
// can ask for a long minimum-norm step.
bool takeStep(GaitEvaluationCache& cache, const GaitParameters& dx,
              const std::optional<double>& speed, double interior, GaitParameters& x) {
  const double before = violation(cache, x, speed, interior);
  for (double t = 1.0; t > std::ldexp(1.0, -kMaxHalvings); t *= 0.5) {
    const GaitParameters trial = x + t * dx;
    if (violation(cache, trial, speed, interior) < before) {
      x = trial;
      return true;
    }
  }
  return false;
}

// Least-squares multipliers of the active rows for ∇f + J_Aᵀλ = 0 (scaled parameters).
void certify(const ActiveSystem& s, const GaitParameters& grad_f, const GaitParameters& D,
             ActiveSetClosing& out) {
  const VectorX gf = grad_f.cwiseProduct(D);
  const VectorX lambda = s.J.transpose().completeOrthogonalDecomposition().solve(-gf);
  out.kkt_residual = (gf + s.J.transpose() * lambda).norm() / std::max(gf.norm(), 1e-300);
  out.min_multiplier = s.inequalities > 0 ? lambda.head(s.inequalities).minCoeff() : 0.0;
}

}  // namespace

ActiveSetClosing closeActiveSet(GaitEvaluationCache& cache, const GaitParameters& start,
                                Criterion criterion, const std::optional<double>& speed,
                                double feasibility_tol, double interior) {
  const GaitEvaluator& ev = cache.evaluator();
  const GaitParameters D = parameterScales(ev.options().parameterisation);
  ActiveSetClosing out;
  out.x = start;
  std::vector<int> active;
  for (;; ++out.iterations) {
    const GaitGradient& gr = cache.gradient(out.x);
    if (!gr.value.motion_computed) return out;
    growActiveSet(ev, gr.value, interior, active);
    const ActiveSystem s = activeSystem(ev, gr, active, speed, D, interior);
    out.active = static_cast<int>(s.r.size());
    const bool converged = s.r.size() == 0 || s.r.cwiseAbs().maxCoeff() <= kNewtonResidual;
    if (!converged && out.iterations < kMaxNewtonSteps) {
      const VectorX dy = s.J.completeOrthogonalDecomposition().solve(-s.r);  // minimum norm
      if (takeStep(cache, GaitParameters(dy.cwiseProduct(D)), speed, interior, out.x)) continue;
    }
    // Judged where the steps stop, also when no step lowers the violation any more: a row
    // identically at its bound (a degenerate row left out of the system) keeps the
    // violation at `interior` however well the other rows are met (measured: the speed
    // closed from 1.1e-5 to 1e-10 m/s in one step, then refused as "not feasible").
    out.feasible = meets(ev, gr.value, speed, feasibility_tol);
    if (s.r.size() > 0) certify(s, criterionGradient(gr, criterion), D, out);
    return out;
  }
}

}  // namespace gaitopt
