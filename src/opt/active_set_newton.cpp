#include "gaitopt/opt/active_set_newton.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <vector>

namespace gaitopt {
namespace {

constexpr int kMaxNewtonSteps = 6;
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
  const int rows = static_cast<int>(active.size()) + (speed ? 1 : 0);
  ActiveSystem s{MatrixX(rows, D.size()), VectorX(rows), static_cast<int>(active.size())};
  for (int i = 0; i < s.inequalities; ++i) {
    const double scale = constraintScale(ev.layout(), ev.model(), active[i]);
    s.r(i) = gr.value.g[active[i]] / scale + interior;
    s.J.row(i) = gr.dg.row(active[i]).cwiseProduct(D.transpose()) / scale;
  }
  if (speed) {
    s.r(rows - 1) = gr.value.speed - *speed;
    s.J.row(rows - 1) = gr.dspeed.cwiseProduct(D).transpose();
  }
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
  for (; out.iterations <= kMaxNewtonSteps; ++out.iterations) {
    const GaitGradient& gr = cache.gradient(out.x);
    if (!gr.value.motion_computed) return out;
    growActiveSet(ev, gr.value, interior, active);
    const ActiveSystem s = activeSystem(ev, gr, active, speed, D, interior);
    out.active = static_cast<int>(s.r.size());
    if (s.r.size() == 0 || s.r.cwiseAbs().maxCoeff() <= kNewtonResidual ||
        out.iterations == kMaxNewtonSteps) {
      out.feasible = meets(ev, gr.value, speed, feasibility_tol);
      if (s.r.size() > 0) certify(s, criterionGradient(gr, criterion), D, out);
      return out;
    }
    const VectorX dy = s.J.completeOrthogonalDecomposition().solve(-s.r);  // minimum norm
    out.x = out.x + GaitParameters(dy.cwiseProduct(D));
  }
  return out;
}

}  // namespace gaitopt
