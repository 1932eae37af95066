#pragma once
// Levels 2–3 of a step evaluation: the SS paths δ(α) through the boundary and interior
// configurations (3.25), the model terms along them, and the zero dynamics of α: Φ (3.14), α̇
// and α̈ (3.15), (3.16) with the saturations (3.54)–(3.56), and the SS timing (3.51).
#include <Eigen/LU>
#include <cmath>
#include <vector>

#include "gaitopt/gait/constraints/impact_landing.hpp"
#include "gaitopt/gait/constraints/zero_dynamics.hpp"
#include "gaitopt/gait/evaluation_context.hpp"
#include "gaitopt/math/chebyshev.hpp"
#include "gaitopt/math/chebyshev_maxima.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"

namespace gaitopt::detail {

template <class S> S squared(const S& x) { return x * x; }

}  // namespace gaitopt::detail

namespace gaitopt {

// Model terms along the SS path at one α, independent of the time law:
// τ = tau_a α̈ + tau_c α̇² + G and the CoM acceleration com_a α̈ + com_c α̇².
template <class S> struct SsPathPoint {
  Vector5<S> q, qs, qss;
  Vector5<S> tau_a, tau_c, G;
  Vector2<S> com_a, com_c, foot2, com;
};

template <class S>
SsPathPoint<S> ssPathPoint(const Model& m, const GaitMotion<S>& mo, const S& alpha) {
  SsPathPoint<S> pt;
  pt.q(0) = alpha;
  pt.qs(0) = S(1.0);
  pt.qss(0) = S(0.0);
  for (int j = 0; j < 4; ++j) {
    const PolyValue<S> v = mo.ss_path[j](alpha);
    pt.q(j + 1) = v.value;
    pt.qs(j + 1) = v.first;
    pt.qss(j + 1) = v.second;
  }
  // With q̇ := q*: C(q, q*) and the CoM terms per unit α̇²; A only through products.
  const ChainState<S> st = chainState(m, pt.q, pt.qs);
  const ChainCoefficients& c = m.pinned;
  const Matrix5<S> Mt = chainInertiaTheta(c, m.inertia, st);
  pt.tau_a = inertiaTimes(m, Mt, pt.qs);  // f = tau_a(0) (3.11)
  pt.tau_c = inertiaTimes(m, Mt, pt.qss) +
             constantTimes(m.theta_map_transpose, chainCoriolisTheta(c, st));  // f' (3.11)
  pt.G = constantTimes(m.theta_map_transpose, chainGravityTheta(c, m.gravity, st));  // G1 = M g x_G
  const double inv_m = 1.0 / m.total_mass;
  pt.com_a = chainPointVelocity(c.b, st) * inv_m;
  pt.com_c = chainPointAcceleration(c.b, st, constantTimes(m.theta_map, pt.qss)) * inv_m;
  pt.foot2 = chainPoint(c.foot2, st);
  pt.com = chainPoint(c.b, st) * inv_m;
  return pt;
}

template <class S> S saturatedF(const S& f, double f_min) {
  return valueOf(f) > f_min ? f : S(f_min);  // (3.54)
}

// dΦ/dα = −2 G₁ f with the saturated f (3.14), (3.54).
template <class S> S phiRate(const SsPathPoint<S>& pt, double f_min) {
  return -2.0 * pt.G(0) * saturatedF(S(pt.tau_a(0)), f_min);
}

// (3.15), (3.16) with the saturated f.
template <class S>
void zeroDynamicsRates(const SsPathPoint<S>& pt, const S& phi, const GaitMotion<S>& mo,
                       double f_min, S& alphadot, S& alphaddot) {
  using std::sqrt;
  const S f = saturatedF(S(pt.tau_a(0)), f_min);
  const S sigma2 = phi + detail::squared(S(mo.f_iSS * mo.alphadot_iSS));
  alphadot = -sqrt(valueOf(sigma2) > 0.0 ? sigma2 : S(1e-300)) / f;
  alphaddot = -(pt.G(0) + pt.tau_c(0) * alphadot * alphadot) / f;
}

}  // namespace gaitopt

namespace gaitopt::detail {

// ∂q/∂α at an SS boundary: δ1*, δ2* given, δ3*, δ4* from zero foot-2 velocity D2 q* = 0 (3.20).
template <class S>
Vector5<S> liftOffSlopes(const Model& m, const Vector5<S>& q, const S& d1s, const S& d2s) {
  const ChainState<S> st = chainState(m, q, Vector5<S>(Vector5<S>::Zero()));
  const Matrix25<S> D2 = chainPointJacobian(m, m.pinned.foot2, st);
  Eigen::Matrix<S, 2, 2> D34;
  D34 << D2(0, 3), D2(0, 4), D2(1, 3), D2(1, 4);
  const Vector2<S> rhs = -(D2.col(0) + D2.col(1) * d1s);
  const Vector2<S> s34 = D34.inverse() * rhs;
  return Vector5<S>(S(1.0), d1s, d2s, s34(0), s34(1));
}

template <class S> void buildSsPaths(EvalContext<S>& c, Vector5<S>& qs_iSS, Vector5<S>& qs_fSS) {
  const GaitVector<S>& p = c.p;
  GaitMotion<S>& mo = c.out.motion;
  const Parameterisation& par = c.options.parameterisation;
  qs_iSS = par.hasDoubleSupport() ? liftOffSlopes(c.model, mo.q_iSS, p(kDelta1sISS), p(kDelta2sISS))
                                  : mo.landing.slopes_after;  // post-impact start
  qs_fSS = par.landsWithImpact() ? mo.landing.slopes_before
                                 : liftOffSlopes(c.model, mo.q_fSS, p(kDelta1sFSS), p(kDelta2sFSS));
  std::vector<S> alphas;
  for (const Vector5<S>& q : mo.q_ss_points) alphas.push_back(q(0));
  for (int j = 0; j < 4; ++j) {  // (3.25), or higher degree with more interior points
    std::vector<S> values;
    for (const Vector5<S>& q : mo.q_ss_points) values.push_back(q(j + 1));
    mo.ss_path[j] = pathThrough(par.basis, mo.alpha_iSS, mo.q_iSS(j + 1), qs_iSS(j + 1), alphas,
                                values, mo.alpha_fSS, mo.q_fSS(j + 1), qs_fSS(j + 1));
  }
}

// Start rate of an SS that follows an impact directly. The zero dynamics conserve σ² − Φ with
// σ = f α̇ (3.14), the impact maps α̇_fSS to λ α̇_fSS, so σ_i = r σ_f with r = f_i λ / f_f and
// σ_f² = σ_i² + Φ_f: the cyclic motion has σ_i² = r² Φ_f / (1 − r²). Requires r² < 1 (the
// orbit of the zero dynamics is then attractive, as for the HZD walkers) and α̇_i² ≥ ε², the
// latter multiplied by 1 − r² so that its value stays finite as r² → 1.
template <class S>
S cyclicStartRate(EvalContext<S>& c, const std::vector<SsPathPoint<S>>& pts, ConstraintState st) {
  using std::sqrt;
  const GaitMotion<S>& mo = c.out.motion;
  const S f_f = saturatedF(S(pts.back().tau_a(0)), c.options.f_min);
  const S r2 = squared(S(mo.f_iSS * mo.landing.rate_ratio / f_f));
  const S phi_f = mo.ss_phi(mo.ss_phi.size() - 1);
  c.set(kImpactOrbit, 0, impactOrbitRow(r2), st);
  c.set(kAlphadotNegative, 0,
        alphadotCyclicRow(r2, phi_f, mo.f_iSS, c.options.alphadot_margin), st);
  const S sigma2 = valueOf(r2) < 1.0 ? S(r2 * phi_f / (1.0 - r2)) : S(0.0);
  return valueOf(sigma2) > 0.0 ? S(-sqrt(sigma2) / mo.f_iSS) : S(0.0);
}

template <class S> void zeroDynamicsStage(EvalContext<S>& c, std::vector<SsPathPoint<S>>& pts) {
  using std::sqrt;
  const GaitOptions& o = c.options;
  GaitMotion<S>& mo = c.out.motion;
  const int n = c.ss_grid.size();
  const auto alphas = mappedNodes(c.ss_grid, mo.alpha_iSS, mo.alpha_fSS);
  Eigen::Matrix<S, Eigen::Dynamic, 1> dphi(n);
  pts.resize(n);
  const ConstraintState st = c.stateAbove(1);
  for (int k = 0; k < n; ++k) {
    pts[k] = ssPathPoint(c.model, mo, S(alphas(k)));
    c.set(kFPositive, k, fPositiveRow(S(pts[k].tau_a(0)), o.f_min), st);  // (3.45)
    dphi(k) = phiRate(pts[k], o.f_min);
  }
  mo.ss_phi = cumulativeOverInterval(c.ss_grid, dphi, mo.alpha_iSS, mo.alpha_fSS);
  mo.f_iSS = saturatedF(S(pts[0].tau_a(0)), o.f_min);

  const ConstraintState st3 = c.stateAbove(2);
  const bool cyclic_ss = !o.parameterisation.hasDoubleSupport();
  const S a_i = cyclic_ss ? cyclicStartRate(c, pts, st3) : c.p(kAlphadotISS);
  if (!cyclic_ss) c.set(kAlphadotNegative, 0, alphadotNegativeRow(a_i, o.alphadot_margin), st3);
  for (int k = 0; k < n; ++k)
    c.set(kNoFallBack, k, noFallBackRow(S(mo.ss_phi(k)), mo.f_iSS, a_i, o.alphadot_margin), st3);
  // (3.56), with the corrected sign of ε (α̇ < 0). Φ_min is the minimum of Φ's interpolant
  // over the whole SS, not its smallest node value: that one depends on the grid (a finer grid
  // finds a lower Φ between two nodes), and so would α̇_iSS, the speed and every force wherever
  // the cap binds.
  const S phi_min = interpolantMinimum(c.ss_grid, mo.ss_phi);
  const S a_min = valueOf(phi_min) < 0.0 ? S(-sqrt(S(-phi_min)) / mo.f_iSS) : S(0.0);
  const S a_cap = a_min - o.alphadot_margin;
  mo.alphadot_iSS = valueOf(a_i) < valueOf(a_cap) ? a_i : a_cap;

  mo.ss_alphadot.resize(n);
  mo.ss_alphaddot.resize(n);
  for (int k = 0; k < n; ++k)
    zeroDynamicsRates(pts[k], mo.ss_phi(k), mo, o.f_min, mo.ss_alphadot(k), mo.ss_alphaddot(k));
  const Eigen::Matrix<S, Eigen::Dynamic, 1> inv_rate = mo.ss_alphadot.cwiseInverse();
  mo.ss_time = cumulativeOverInterval(c.ss_grid, inv_rate, mo.alpha_iSS, mo.alpha_fSS);  // (3.51)
  mo.T_SS = mo.ss_time(n - 1);
  mo.alphadot_fSS = mo.ss_alphadot(n - 1);
}

}  // namespace gaitopt::detail
