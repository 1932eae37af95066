#pragma once
// Level 4 of a step evaluation: the DS polynomials α(t), δ1(α), δ2(α) from the leg exchange
// (3.22)–(3.27) with the κ-normalisation, the prescribed DS coordinates they give at a time,
// and the reach of the rear foot along the DS (3.41).
#include <array>
#include <vector>

#include "gaitopt/gait/boundary_geometry.hpp"
#include "gaitopt/gait/constraints/reach.hpp"
#include "gaitopt/gait/constraints/zero_dynamics.hpp"
#include "gaitopt/gait/evaluation_context.hpp"

namespace gaitopt {

// Prescribed DS coordinates α, δ1, δ2 and their rates at time t.
template <class S> struct DsPrescribed {
  S alpha, alphad, alphadd, d1, d1d, d1dd, d2, d2d, d2dd;
};

template <class S> DsPrescribed<S> dsPrescribed(const GaitMotion<S>& mo, const S& t) {
  DsPrescribed<S> r;
  const PolyValue<S> a = mo.ds_alpha(t);
  r.alpha = a.value;
  r.alphad = a.first;
  r.alphadd = a.second;
  const PolyValue<S> d1 = mo.ds_delta1(r.alpha), d2 = mo.ds_delta2(r.alpha);
  r.d1 = d1.value;
  r.d1d = d1.first * r.alphad;
  r.d1dd = d1.second * r.alphad * r.alphad + d1.first * r.alphadd;
  r.d2 = d2.value;
  r.d2d = d2.first * r.alphad;
  r.d2dd = d2.second * r.alphad * r.alphad + d2.first * r.alphadd;
  return r;
}

}  // namespace gaitopt

namespace gaitopt::detail {

// DS polynomials from the leg exchange (3.22)–(3.24) with the κ-normalisation.
template <class S> void dsBoundaryStage(EvalContext<S>& c, const Vector5<S>& qs_iSS,
                                        const Vector5<S>& qs_fSS) {
  GaitMotion<S>& mo = c.out.motion;
  const GaitVector<S>& p = c.p;
  const Parameterisation& par = c.options.parameterisation;
  S alphadot_iDS, d1s_iDS, d2s_iDS;
  if (par.landsWithImpact()) {  // the DS starts with the post-impact velocity
    mo.kappa = mo.landing.rate_ratio;
    alphadot_iDS = mo.kappa * mo.alphadot_fSS;
    d1s_iDS = mo.landing.slopes_after(1);
    d2s_iDS = mo.landing.slopes_after(2);
  } else {
    mo.kappa = 1.0 + qs_fSS(1) + qs_fSS(3) - qs_fSS(4);
    c.set(kKappaPositive, 0, kappaPositiveRow(mo.kappa, c.options.kappa_min), c.stateAbove(3));
    const S kappa = valueOf(mo.kappa) > c.options.kappa_min ? mo.kappa : S(c.options.kappa_min);
    alphadot_iDS = kappa * mo.alphadot_fSS;
    d1s_iDS = qs_fSS(4) / kappa;
    d2s_iDS = (qs_fSS(2) + qs_fSS(3)) / kappa;
  }
  std::vector<S> alphas, d1, d2;
  for (int k = 0; k < par.ds_points; ++k) {
    const int i = par.dsPointIndex(k);
    alphas.push_back(p(kAlphaIDS) + par.dsFraction(k) * (p(kAlphaFDS) - p(kAlphaIDS)));
    d1.push_back(p(i));
    d2.push_back(delta2FromTheta3(alphas.back(), p(i), p(i + 1)));
  }
  mo.ds_delta1 = pathThrough(par.basis, p(kAlphaIDS), p(kDelta1IDS), d1s_iDS, alphas, d1,
                             p(kAlphaFDS), p(kDelta1FDS), S(qs_iSS(1)));  // (3.26)
  mo.ds_delta2 = pathThrough(par.basis, p(kAlphaIDS), S(mo.q_iDS(2)), d2s_iDS, alphas, d2,
                             p(kAlphaFDS), S(mo.q_fDS(2)), S(qs_iSS(2)));
  mo.ds_alpha = cubicHermite(S(0.0), p(kAlphaIDS), alphadot_iDS, p(kTDS), p(kAlphaFDS),
                             mo.alphadot_iSS);  // (3.27)
}

template <class S> bool dsReachStage(EvalContext<S>& c) {
  GaitMotion<S>& mo = c.out.motion;
  const auto ts = mappedNodes(c.ds_grid, S(0.0), mo.T_DS);
  const double L = c.model.robot.l4 + c.model.robot.l5;
  const ConstraintState st = c.stateAbove(3);
  bool reachable = true;  // the DS inverse kinematics exists at every node
  for (int k = 0; k < c.ds_grid.size(); ++k) {
    const DsPrescribed<S> pr = dsPrescribed(mo, S(ts(k)));
    const S rho2 = rearFootFromHip(c.model, pr.alpha, pr.d1, mo.d).squaredNorm();
    const std::array<S, 2> g = reachRows(rho2, L, c.options.reach_margin);
    c.set(kDsReachMax, k, g[0], st);  // (3.41)
    c.set(kDsReachMin, k, g[1], st);
    reachable = reachable && valueOf(rho2) < L * L && valueOf(rho2) > 0.0;
  }
  return reachable;
}

}  // namespace gaitopt::detail
