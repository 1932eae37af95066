#pragma once
// Evaluation of one walking step from its parameters (§3.3), templated on the scalar so the
// same code yields values (double) and exact gradients (forward-mode AD). The stages follow the
// hierarchy: boundary geometry (levels 0–1, gait/boundary_geometry.hpp), zero dynamics and DS
// boundary (levels 2–4, gait/zero_dynamics.hpp, gait/ds_path.hpp, with the saturations
// (3.54)–(3.56)), then the full motion (level 5, gait/phase_constraints.hpp, and the criteria,
// gait/criteria_quadrature.hpp).
#include <array>
#include <cmath>
#include <vector>

#include "gaitopt/gait/boundary_geometry.hpp"
#include "gaitopt/gait/constraints/touchdown_speed.hpp"
#include "gaitopt/gait/criteria_quadrature.hpp"
#include "gaitopt/gait/ds_path.hpp"
#include "gaitopt/gait/evaluation_context.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/phase_constraints.hpp"
#include "gaitopt/gait/phase_sample.hpp"
#include "gaitopt/gait/zero_dynamics.hpp"

namespace gaitopt::detail {

// Level-5 constraints of the DS and its integrals of the criteria integrands.
template <class S> std::array<S, 4> dsMotionStage(EvalContext<S>& c, ConstraintState st) {
  GaitMotion<S>& mo = c.out.motion;
  const GaitOptions& o = c.options;
  const int nds = c.ds_grid.size();
  IntegrandValues<S> ds_int = integrandValues<S>(nds);
  const auto ts = mappedNodes(c.ds_grid, S(0.0), mo.T_DS);
  std::vector<std::array<double, 6>> switching(nds);
  std::vector<int> branch(nds);
  for (int k = 0; k < nds; ++k) {
    const PhaseSample<S> s = dsSample(c.model, o, mo, S(ts(k)));
    for (int i = 0; i < 6; ++i) switching[k][i] = valueOf(s.switching[i]);
    branch[k] = s.branch;
    dsConstraintValues(c, k, s, layoutWriter(c, st));
    for (int j = 0; j < 4; ++j) c.out.ds_joint_speeds.push_back(s.omega(j));
    setIntegrands(c.model, s, k, S(1.0), ds_int);
  }
  c.out.ds_pieces = c.known_pieces ? *c.known_pieces : dsPieces(c, ts, branch, switching);
  return c.out.ds_pieces.switch_times.empty()
             ? integrateCriteria(c.ds_grid, ds_int, S(0.0), mo.T_DS, c.out.criteria_kinks,
                                 c.out.torque_residuals)
             : integrateDsPiecewise(c, c.out.ds_pieces);
}

template <class S>
void motionStage(EvalContext<S>& c, const std::vector<SsPathPoint<S>>& pts) {
  GaitMotion<S>& mo = c.out.motion;
  const GaitOptions& o = c.options;
  const ConstraintState st = c.stateAbove(4);
  const int nss = c.ss_grid.size();
  IntegrandValues<S> ss_int = integrandValues<S>(nss);
  for (int k = 0; k < nss; ++k) {
    const S& ad = mo.ss_alphadot(k);
    const PhaseSample<S> s = ssSample(c.model, pts[k], ad, mo.ss_alphaddot(k));
    ssConstraintValues(c, k, nss, s, layoutWriter(c, st));
    for (int j = 0; j < 4; ++j) c.out.ss_joint_speeds.push_back(s.omega(j));
    setIntegrands(c.model, s, k, ad, ss_int);  // dt = dα / α̇ (3.29)
  }
  if (c.layout.has(kTouchdownSpeed))  // the arriving foot's speed at the SS end's rate
    c.set(kTouchdownSpeed, 0,
          touchdownSpeedRow(S(mo.landing.v2_minus(1)), mo.alphadot_fSS, o.touchdown_speed_min), st);
  const std::array<S, 4> ss_total = ssCriteria(c, pts, ss_int);
  c.out.ss_criteria_kinks = static_cast<int>(c.out.criteria_kinks.size());
  // Without DS the impact's energy loss is resupplied by the motors within the SS (cyclicity).
  std::array<S, 4> ds_total{S(0.0), S(0.0), S(0.0), S(0.0)};
  if (o.parameterisation.hasDoubleSupport()) ds_total = dsMotionStage(c, st);
  std::array<S, 4> crit;
  for (int i = 0; i < 4; ++i) crit[i] = (ss_total[i] + ds_total[i]) / mo.d;  // (3.28)
  c.out.C_Gamma = crit[0];
  c.out.C_E = crit[1];
  c.out.W = crit[2];
  c.out.C_frott = crit[3];
  using std::sqrt;
  const S root_d = sqrt(mo.d);
  for (S& r : c.out.torque_residuals) r /= root_d;
  c.out.motion_computed = true;
}

template <class S> bool allFinite(const GaitEvaluation<S>& out) {
  for (std::size_t k = 0; k < out.g.size(); ++k)
    if (out.state[k] != ConstraintState::NotComputed && !std::isfinite(valueOf(out.g[k])))
      return false;
  for (const S* x : {&out.C_Gamma, &out.C_E, &out.W, &out.C_frott, &out.T_SS, &out.speed})
    if (!std::isfinite(valueOf(*x))) return false;
  return true;
}

// A motion whose numbers overflow (a degenerate phase, e.g. a DS with almost no α range) is
// reported as undefined at level 4, the level of the DS existence, never as NaN.
template <class S> void discardNonFiniteMotion(EvalContext<S>& c) {
  GaitEvaluation<S>& out = c.out;
  for (std::size_t k = 0; k < out.g.size(); ++k)
    if (c.layout.levelOf(static_cast<int>(k)) >= 4 || !std::isfinite(valueOf(out.g[k]))) {
      out.g[k] = S(0.0);
      out.state[k] = ConstraintState::NotComputed;
    }
  out.C_Gamma = out.C_E = out.W = out.C_frott = S(0.0);
  out.criteria_kinks.clear();
  out.torque_residuals.clear();
  out.ss_joint_speeds.clear();
  out.ds_joint_speeds.clear();
  out.ds_piece_speeds.clear();
  out.ss_criteria_kinks = 0;
  out.ds_piece_g.clear();
  out.ds_piece_bounds.clear();
  if (!std::isfinite(valueOf(out.T_SS)) || !std::isfinite(valueOf(out.speed)))
    out.T_SS = out.speed = out.alphadot_fSS = S(0.0);
  out.motion_computed = false;
  out.numerically_undefined = true;
  out.failed_level = 4;
}

template <class S>
void evaluateGaitImpl(const Model& model, const GaitOptions& options,
                      const ConstraintLayout& layout, const GaitGrids& grids,
                      const GaitVector<S>& p, GaitEvaluation<S>& out,
                      const DsPieces* known_pieces = nullptr, bool record_pieces = true) {
  out = GaitEvaluation<S>();
  out.g.assign(layout.size(), S(0.0));
  out.state.assign(layout.size(), ConstraintState::NotComputed);
  const GaitVector<S> pe = landingParameters(p, options.parameterisation);
  EvalContext<S> c{model, options, layout, grids.ss,     grids.ss_criteria, grids.ds,
                   grids.ds_piece, pe, out, known_pieces, record_pieces};
  const bool boundary_ok = boundaryStage(c);
  const bool ds = options.parameterisation.hasDoubleSupport();
  out.step_length = pe(kStepLength);
  out.T_DS = pe(kTDS);
  if (boundary_ok) {
    Vector5<S> qs_iSS, qs_fSS;
    buildSsPaths(c, qs_iSS, qs_fSS);
    std::vector<SsPathPoint<S>> pts;
    zeroDynamicsStage(c, pts);
    if (ds) dsBoundaryStage(c, qs_iSS, qs_fSS);
    out.T_SS = out.motion.T_SS;
    out.alphadot_fSS = out.motion.alphadot_fSS;
    out.speed = out.step_length / (out.T_SS + out.T_DS);  // (3.50)
    if (!ds || dsReachStage(c)) motionStage(c, pts);
  }
  out.failed_level = c.lowestViolated(5);
  if (!allFinite(out)) discardNonFiniteMotion(c);
}

}  // namespace gaitopt::detail
