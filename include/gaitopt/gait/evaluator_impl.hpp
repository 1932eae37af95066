#pragma once
// Evaluation of one walking step from its parameters (§3.3), templated on the scalar so the
// same code yields values (double) and exact gradients (forward-mode AD). Stages follow the
// hierarchy: boundary geometry (levels 0–1), zero dynamics and DS boundary (levels 2–4, with the
// saturations (3.54)–(3.56)), then the full motion (level 5 and criteria).
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "gaitopt/math/bracketed_root.hpp"
#include "gaitopt/math/chebyshev.hpp"
#include "gaitopt/math/chebyshev_abs_integral.hpp"
#include "gaitopt/gait/ds_force_distribution.hpp"
#include "gaitopt/gait/evaluation.hpp"
#include "gaitopt/gait/impact_landing.hpp"
#include "gaitopt/gait/options.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"
#include "gaitopt/gait/leg_geometry.hpp"
#include "gaitopt/model/torque_envelope.hpp"

namespace gaitopt::detail {

template <class S> struct EvalContext {
  const Model& model;
  const GaitOptions& options;
  const ConstraintLayout& layout;
  const ChebyshevGrid& ss_grid;
  const ChebyshevGrid& ss_criteria_grid;  // W and C_E in the SS (GaitGrids::ss_criteria)
  const ChebyshevGrid& ds_grid;
  const ChebyshevGrid& piece_grid;
  const GaitVector<S>& p;
  GaitEvaluation<S>& out;
  const DsPieces* known_pieces;  // DS quadrature pieces found by a double pass, or null
  bool record_pieces;            // GaitEvaluation::ds_piece_g wanted

  void set(int group, int index, const S& value, ConstraintState state) {
    const int k = layout[group].offset + index;
    out.g[k] = value;
    out.state[k] = state;
  }
  // Lowest level ≤ max_level with a violated computed entry, or −1.
  int lowestViolated(int max_level) const {
    int lowest = -1;
    for (int k = 0; k < layout.size(); ++k)
      if (out.state[k] != ConstraintState::NotComputed && layout.levelOf(k) <= max_level &&
          valueOf(out.g[k]) > 0.0 && (lowest < 0 || layout.levelOf(k) < lowest))
        lowest = layout.levelOf(k);
    return lowest;
  }
  ConstraintState stateAbove(int level) const {
    const int failed = lowestViolated(level);
    return failed < 0 ? ConstraintState::Defined : ConstraintState::Extended;
  }
};

template <class S> S squared(const S& x) { return x * x; }

// ---------------------------------------------------------------------------------------------
// Levels 0–1: boundary configurations.

// Hip-to-foot-2 vector with foot 2 on the ground at x = −d (corrected (3.18)).
template <class S>
Vector2<S> rearFootFromHip(const Model& m, const S& alpha, const S& delta1, const S& d) {
  const Vector2<S> f1 = foot1FromHip(m, alpha, delta1);
  return Vector2<S>(f1(0) - d, f1(1));
}

template <class S>
void setReach(EvalContext<S>& c, int max_group, const Vector2<S>& r, ConstraintState st) {
  const double L = c.model.robot.l4 + c.model.robot.l5;
  const S rho2 = r.squaredNorm();
  c.set(max_group, 0, rho2 - L * L + c.options.reach_margin, st);  // (3.36), (3.37)
  c.set(max_group + 1, 0, c.options.reach_margin - rho2, st);
}

template <class S>
Vector5<S> dsConfiguration(const Model& m, const S& alpha, const S& delta1, const S& theta3,
                           const Vector2<S>& r) {
  const Vector2<S> leg2 = leg2InverseKinematics(m, alpha, delta1, r);
  return Vector5<S>(alpha, delta1, delta2FromTheta3(alpha, delta1, theta3), leg2(0), leg2(1));
}

// Touchdown with impact (gait/impact_landing.hpp): the pre-impact slopes are parameters, the
// impact's arrival, behaviour consistency and rate ratio are level-1 constraints, since the
// step's boundary conditions (the next phase's initial slopes) depend on them.
// When the touchdown configuration is out of reach (level 0 fails) the impact runs, as an
// extension, on the rear leg stretched or folded to the reach limit along the hip–foot line,
// so that the level-1 projection always has values.
template <class S> void impactLandingStage(EvalContext<S>& c, const Vector2<S>& r_iDS, bool ids_ok) {
  constexpr double kArrivalMargin = 1e-3;  // V2z⁻ per unit rate [m/s per rad/s]
  const Parameterisation& par = c.options.parameterisation;
  const GaitVector<S>& p = c.p;
  GaitMotion<S>& mo = c.out.motion;
  Vector5<S> q = mo.q_fSS;
  if (!ids_ok) {
    using std::sqrt;
    const double L = c.model.robot.l4 + c.model.robot.l5;
    const S rho = sqrt(S(r_iDS.squaredNorm() + 1e-300));
    const double lo = 1e-2 * L, hi = (1.0 - 1e-6) * L, v = valueOf(rho);
    const S reach = v < lo ? S(lo) : v > hi ? S(hi) : rho;
    const Vector2<S> r = r_iDS * S(reach / rho);
    q = exchangeLegs(dsConfiguration(c.model, p(kAlphaIDS), p(kDelta1IDS), p(kTheta3IDS), r));
  }
  const int i = par.impactSlopeIndex();
  const Vector5<S> slopes(S(1.0), p(kDelta1sFSS), p(kDelta2sFSS), p(i), p(i + 1));
  mo.landing = landingImpact(c.model, q, slopes, par.landing, c.options.friction_coefficient);
  const ConstraintState st = c.stateAbove(0);
  c.set(kImpactArrival, 0, mo.landing.v2_minus(1) + kArrivalMargin, st);  // (2.2)
  std::vector<S> g;
  landingConsistency(c.model, mo.landing, par.landing, g);
  for (std::size_t k = 0; k < g.size(); ++k) c.set(kImpactConsistency, static_cast<int>(k), g[k], st);
  c.set(kImpactRateRatio, 0, c.options.kappa_min - mo.landing.rate_ratio, st);
}

template <class S> bool boundaryStage(EvalContext<S>& c) {
  const GaitVector<S>& p = c.p;
  const Model& m = c.model;
  GaitMotion<S>& mo = c.out.motion;
  const auto D = ConstraintState::Defined;
  mo.d = p(kStepLength);
  mo.T_DS = p(kTDS);
  const Vector2<S> r_iDS = rearFootFromHip(m, p(kAlphaIDS), p(kDelta1IDS), mo.d);
  const Vector2<S> r_fDS = rearFootFromHip(m, p(kAlphaFDS), p(kDelta1FDS), mo.d);
  setReach(c, kReachMaxIDS, r_iDS, D);
  if (c.layout.has(kReachMaxFDS)) setReach(c, kReachMaxFDS, r_fDS, D);

  const double L = m.robot.l4 + m.robot.l5;
  const bool ids_ok = valueOf(r_iDS.squaredNorm()) < L * L && valueOf(r_iDS.squaredNorm()) > 0.0;
  if (ids_ok) {
    mo.q_iDS = dsConfiguration(m, p(kAlphaIDS), p(kDelta1IDS), p(kTheta3IDS), r_iDS);
    mo.q_fSS = exchangeLegs(mo.q_iDS);  // (3.22)
    mo.alpha_fSS = mo.q_fSS(0);
  } else {
    using std::atan2;  // (3.53): rear tibia along the ankle–hip axis
    mo.alpha_fSS = atan2(r_iDS(0), -r_iDS(1));
  }
  mo.alpha_iSS = p(kAlphaFDS);  // (3.21)
  const Parameterisation& par = c.options.parameterisation;
  mo.q_ss_points.assign(par.ss_points, Vector5<S>(Vector5<S>::Zero()));
  Vector2<S> r_int;
  for (int k = 0; k < par.ss_points; ++k) {
    const int i = par.ssPointIndex(k);
    const S alpha = mo.alpha_iSS + par.ssFraction(k) * (mo.alpha_fSS - mo.alpha_iSS);
    mo.q_ss_points[k] << alpha, p(i), delta2FromTheta3(alpha, p(i), p(i + 1)), p(i + 2), p(i + 3);
    if (!par.isFootPoint(k)) continue;
    const Vector2<S> f1 = foot1FromHip(m, alpha, p(i));
    r_int = Vector2<S>(p(i + 2), f1(1) + p(i + 3));  // (3.19)
    setReach(c, kReachMaxInt, r_int, D);
  }
  const double am = c.options.angle_margin;
  if (c.layout.has(kAlphaOrderDS))
    c.set(kAlphaOrderDS, 0, p(kAlphaFDS) - p(kAlphaIDS) + c.options.ds_alpha_range_min, D);  // (3.38)
  c.set(kAlphaOrderSS, 0, mo.alpha_fSS - p(kAlphaFDS) + am, D);
  c.set(kTibiaFront, 0, p(kAlphaIDS) - 0.5 * M_PI + am, D);  // (3.40)
  c.set(kTibiaRear, 0, -0.5 * M_PI - mo.alpha_fSS + am, D);
  if (par.landsWithImpact()) impactLandingStage(c, r_iDS, ids_ok);
  if (c.lowestViolated(1) >= 0) return false;

  mo.q_fDS = dsConfiguration(m, p(kAlphaFDS), p(kDelta1FDS), p(kTheta3FDS), r_fDS);
  mo.q_iSS = mo.q_fDS;
  const int mid = par.ss_points / 2;
  mo.q_ss_points[mid] = dsConfiguration(m, S(mo.q_ss_points[mid](0)), p(kDelta1Int),
                                        p(kTheta3Int), r_int);
  return true;
}

// ---------------------------------------------------------------------------------------------
// Levels 2–4: SS polynomials, zero dynamics, DS boundary.

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
  const S sigma2 = phi + squared(S(mo.f_iSS * mo.alphadot_iSS));
  alphadot = -sqrt(valueOf(sigma2) > 0.0 ? sigma2 : S(1e-300)) / f;
  alphaddot = -(pt.G(0) + pt.tau_c(0) * alphadot * alphadot) / f;
}

// Start rate of an SS that follows an impact directly. The zero dynamics conserve σ² − Φ with
// σ = f α̇ (3.14), the impact maps α̇_fSS to λ α̇_fSS, so σ_i = r σ_f with r = f_i λ / f_f and
// σ_f² = σ_i² + Φ_f: the cyclic motion has σ_i² = r² Φ_f / (1 − r²). Requires r² < 1 (the
// orbit of the zero dynamics is then attractive, as for the HZD walkers) and α̇_i² ≥ ε², the
// latter multiplied by 1 − r² so that its value stays finite as r² → 1.
template <class S>
S cyclicStartRate(EvalContext<S>& c, const std::vector<SsPathPoint<S>>& pts, ConstraintState st) {
  using std::sqrt;
  constexpr double kOrbitMargin = 1e-3;
  const GaitMotion<S>& mo = c.out.motion;
  const S f_f = saturatedF(S(pts.back().tau_a(0)), c.options.f_min);
  const S r2 = squared(S(mo.f_iSS * mo.landing.rate_ratio / f_f));
  const S phi_f = mo.ss_phi(mo.ss_phi.size() - 1);
  c.set(kImpactOrbit, 0, r2 - (1.0 - kOrbitMargin), st);
  c.set(kAlphadotNegative, 0,
        squared(c.options.alphadot_margin) * (1.0 - r2) - r2 * phi_f / squared(mo.f_iSS), st);
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
    c.set(kFPositive, k, o.f_min - pts[k].tau_a(0), st);  // (3.45)
    dphi(k) = phiRate(pts[k], o.f_min);
  }
  mo.ss_phi = cumulativeOverInterval(c.ss_grid, dphi, mo.alpha_iSS, mo.alpha_fSS);
  mo.f_iSS = saturatedF(S(pts[0].tau_a(0)), o.f_min);

  const ConstraintState st3 = c.stateAbove(2);
  const bool cyclic_ss = !o.parameterisation.hasDoubleSupport();
  const S a_i = cyclic_ss ? cyclicStartRate(c, pts, st3) : c.p(kAlphadotISS);
  if (!cyclic_ss) c.set(kAlphadotNegative, 0, a_i + o.alphadot_margin, st3);
  int worst = 0;
  for (int k = 0; k < n; ++k) {
    // (3.55) divided by f_i²: a margin ε² on σ²/f_i².
    c.set(kNoFallBack, k,
          -(mo.ss_phi(k) / squared(mo.f_iSS) + a_i * a_i) + squared(o.alphadot_margin), st3);
    if (valueOf(mo.ss_phi(k)) < valueOf(mo.ss_phi(worst))) worst = k;
  }
  // (3.56), with the corrected sign of ε (α̇ < 0).
  const S phi_min = mo.ss_phi(worst);
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
    c.set(kKappaPositive, 0, c.options.kappa_min - mo.kappa, c.stateAbove(3));
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

template <class S> bool dsReachStage(EvalContext<S>& c) {
  GaitMotion<S>& mo = c.out.motion;
  const auto ts = mappedNodes(c.ds_grid, S(0.0), mo.T_DS);
  const double L = c.model.robot.l4 + c.model.robot.l5;
  const ConstraintState st = c.stateAbove(3);
  bool reachable = true;  // the DS inverse kinematics exists at every node
  for (int k = 0; k < c.ds_grid.size(); ++k) {
    const DsPrescribed<S> pr = dsPrescribed(mo, S(ts(k)));
    const S rho2 = rearFootFromHip(c.model, pr.alpha, pr.d1, mo.d).squaredNorm();
    c.set(kDsReachMax, k, rho2 - L * L + c.options.reach_margin, st);  // (3.41)
    c.set(kDsReachMin, k, c.options.reach_margin - rho2, st);
    reachable = reachable && valueOf(rho2) < L * L && valueOf(rho2) > 0.0;
  }
  return reachable;
}

// ---------------------------------------------------------------------------------------------
// Level 5 and criteria.

template <class S> struct PhaseSample {
  int branch = 0;  // DS force-distribution formula (gait/ds_force_distribution.hpp)
  std::array<S, 6> switching{};
  Vector5<S> q, qd, qdd;
  Vector4<S> gamma_star, omega;
  Vector2<S> R1, R2, foot2, com;
};

template <class S>
PhaseSample<S> ssSample(const Model& m, const SsPathPoint<S>& pt, const S& alphadot,
                        const S& alphaddot) {
  PhaseSample<S> s;
  const S ad2 = alphadot * alphadot;
  s.q = pt.q;
  s.qd = pt.qs * alphadot;
  s.qdd = pt.qs * alphaddot + pt.qss * ad2;
  const Vector5<S> tau = pt.tau_a * alphaddot + pt.tau_c * ad2 + pt.G;
  s.omega = jointSpeeds(s.qd);
  s.gamma_star = solveDGamma25(Vector4<S>(tau.template tail<4>())) +
                 frictionTorque(m, s.omega, SignMode::Smooth);  // (3.57), (1.21)
  const Vector2<S> acc = pt.com_a * alphaddot + pt.com_c * ad2;
  s.R1 = Vector2<S>(m.total_mass * acc(0), m.total_mass * (acc(1) + m.gravity));  // (1.36)
  s.R2.setZero();
  s.foot2 = pt.foot2;
  s.com = pt.com;
  return s;
}

template <class S>
PhaseSample<S> dsSample(const Model& m, const GaitOptions& o, const GaitMotion<S>& mo,
                        const S& t, int forced_branch = kBranchFree) {
  const DsPrescribed<S> pr = dsPrescribed(mo, t);
  PhaseSample<S> s;
  const Vector2<S> leg2 = leg2InverseKinematics(m, pr.alpha, pr.d1,
                                                rearFootFromHip(m, pr.alpha, pr.d1, mo.d));
  s.q = Vector5<S>(pr.alpha, pr.d1, pr.d2, leg2(0), leg2(1));
  ChainState<S> st = chainState(m, s.q, Vector5<S>(Vector5<S>::Zero()));
  const Matrix25<S> D2 = chainPointJacobian(m, m.pinned.foot2, st);
  Eigen::Matrix<S, 2, 2> D34;
  D34 << D2(0, 3), D2(0, 4), D2(1, 3), D2(1, 4);
  const Eigen::Matrix<S, 2, 2> D34inv = D34.inverse();
  const Vector2<S> v34 = -D34inv * (D2.col(0) * pr.alphad + D2.col(1) * pr.d1d);  // (1.34)
  s.qd = Vector5<S>(pr.alphad, pr.d1d, pr.d2d, v34(0), v34(1));
  st.theta_dot = constantTimes(m.theta_map, s.qd);
  const Vector2<S> H2 = chainPointBias(m.pinned.foot2, st);
  const Vector2<S> a34 = -D34inv * (D2.col(0) * pr.alphadd + D2.col(1) * pr.d1dd + H2);
  s.qdd = Vector5<S>(pr.alphadd, pr.d1dd, pr.d2dd, a34(0), a34(1));  // (1.35)
  const PinnedMotionForces<S> forces = pinnedMotionForces(m, st, s.qdd);
  const DoubleSupportAffine<S> aff = doubleSupportAffine(m, forces, s.qd, SignMode::Smooth);
  const double M = m.total_mass;
  const S R2z0 = aff.R2z0;                                          // (3.58)
  const S R1z0 = M * (aff.com_acceleration(1) + m.gravity) - R2z0;  // (3.59) corrected
  const DsBounds<S> bounds = r2xBounds(R1z0, R2z0, S(M * aff.com_acceleration(0)),
                                       o.friction_coefficient,
                                       forced_branch >= 0 ? forced_branch % 4 : kBranchFree);
  s.omega = jointSpeeds(s.qd);
  const DsChoice<S> choice = o.ds_distribution == DsDistribution::Torque
                                ? r2xMinTorque(aff.J, aff.K, bounds, forced_branch)
                                : r2xMinPower(aff.J, aff.K, s.omega, jouleCoefficient(m), bounds,
                                              forced_branch);
  const S& R2x = choice.r2x;
  s.branch = choice.branch;
  s.switching = choice.switching;
  s.gamma_star = aff.J - aff.K * R2x;  // (3.62)
  s.R2 = Vector2<S>(R2x, R2z0 + aff.R2z_slope * R2x);
  s.R1 = Vector2<S>(M * aff.com_acceleration(0), M * (aff.com_acceleration(1) + m.gravity)) - s.R2;
  s.foot2 = forces.foot2;
  s.com = forces.com;
  return s;
}

// The phase-wise entries of one sample at node k, each passed to put(group, index, value): to
// the layout at a grid node, or to a DS piece's samples (GaitEvaluation::ds_piece_g).
template <class S, class Put>
void phaseConstraintValues(const EvalContext<S>& c, int torque_group, int limits_group, int k,
                           const PhaseSample<S>& s, Put&& put) {
  const RobotParams& r = c.model.robot;
  const double jm = c.options.joint_limit_margin;
  for (int j = 0; j < 4; ++j) {  // (3.46), (3.47)
    const S limit = torqueLimit(r.envelope, s.omega(j), c.options.full_torque_envelope);
    put(torque_group, 8 * k + 2 * j, s.gamma_star(j) - limit);
    put(torque_group, 8 * k + 2 * j + 1, -s.gamma_star(j) - limit);
  }
  const std::array<S, 4> angles = {s.q(1), s.q(2), s.q(2) + s.q(3), s.q(4)};  // (3.42)
  for (int j = 0; j < 4; ++j) {
    const bool knee = j == 0 || j == 3;
    const double lo = knee ? r.limits.knee_min : r.limits.hip_min;
    const double hi = knee ? r.limits.knee_max : r.limits.hip_max;
    put(limits_group, 8 * k + 2 * j, angles[j] - hi + jm);
    put(limits_group, 8 * k + 2 * j + 1, lo - angles[j] + jm);
  }
}

template <class S, class Put>
void contactConstraintValues(const EvalContext<S>& c, int cone_group, int normal_group, int foot,
                             int feet, int k, const Vector2<S>& R, Put&& put) {
  const double f = c.options.friction_coefficient;
  put(cone_group, 2 * (feet * k + foot), -f * R(1) - R(0));  // (3.48)
  put(cone_group, 2 * (feet * k + foot) + 1, -f * R(1) + R(0));
  put(normal_group, feet * k + foot, c.options.min_normal_force - R(1));
}

// The DS level-5 entries (3.42), (3.43), (3.46)–(3.48) of one sample at DS node k.
template <class S, class Put>
void dsConstraintValues(const EvalContext<S>& c, int k, const PhaseSample<S>& s, Put&& put) {
  phaseConstraintValues(c, kTorqueDS, kJointLimitsDS, k, s, put);
  contactConstraintValues(c, kFrictionConeDS, kNormalForceDS, 0, 2, k, s.R1, put);
  contactConstraintValues(c, kFrictionConeDS, kNormalForceDS, 1, 2, k, s.R2, put);
  put(kDsMonotone, k, s.qd(0) - c.options.ds_alphadot_max);
}

// A writer of entries into the layout, all in state st.
template <class S> auto layoutWriter(EvalContext<S>& c, ConstraintState st) {
  return [&c, st](int group, int index, const S& value) { c.set(group, index, value, st); };
}

// Smooth integrands of the criteria at one sample: Γ*ᵀΓ*, Γ*ᵀω, the electrical power P (3.32)
// and the joint powers Γ*_j ω_j. C_E and W integrate max(0, P) and Σ_j |Γ*_j ω_j| (3.147), whose
// kinks integrateCriteria splits at.
constexpr int kTorque2 = 0, kMechanical = 1, kPower = 2, kJointPower = 3, kNumIntegrands = 7;
template <class S>
using IntegrandValues = std::array<Eigen::Matrix<S, Eigen::Dynamic, 1>, kNumIntegrands>;

template <class S> IntegrandValues<S> integrandValues(int nodes) {
  IntegrandValues<S> f;
  for (auto& v : f) v.resize(nodes);
  return f;
}

// Integrands at sample k of a phase per unit of its coordinate x (α in the SS, t in the DS):
// per unit time divided by phase_rate = dx/dt (α̇, or 1).
template <class S>
void setIntegrands(const Model& m, const PhaseSample<S>& s, int k, const S& phase_rate,
                   IntegrandValues<S>& f) {
  const S torque2 = s.gamma_star.squaredNorm();
  const S mech = s.gamma_star.dot(s.omega);
  f[kTorque2](k) = torque2 / phase_rate;
  f[kMechanical](k) = mech / phase_rate;
  f[kPower](k) = (mech + jouleCoefficient(m) * torque2) / phase_rate;
  for (int j = 0; j < 4; ++j) f[kJointPower + j](k) = s.gamma_star(j) * s.omega(j) / phase_rate;
}

// C_Γ, C_E, W, C_frott (times d) over one smooth piece x ∈ [a, b] of a phase, from the
// integrands per unit x at the grid's nodes mapped to [a, b]. Per unit of the grid coordinate s
// they are f·(b − a)/2, positive for a positive integrand per unit time (in the SS, α and s
// decrease with time and α̇ < 0), hence |b − a|/2 times ∫|f| and ∫max(0, ±f) over s ∈ [−1, 1].
// The kinks of max(0, P) and |Γ*_j ω_j| are appended to `kinks`, in x, in time order.
constexpr int kCriterionCGamma = 0, kCriterionCE = 1, kCriterionW = 2, kCriterionCFrott = 3;

// C_Γ and C_frott: smooth integrands, the Clenshaw–Curtis sum.
template <class S>
void integrateSmoothCriteria(const ChebyshevGrid& grid, const IntegrandValues<S>& f, const S& a,
                             const S& b, std::array<S, 4>& r) {
  r[kCriterionCGamma] = integrateOverInterval(grid, f[kTorque2], a, b);
  r[kCriterionCFrott] = integrateOverInterval(grid, f[kMechanical], a, b);
}

// C_E and W: the interpolants split at their roots (math/chebyshev_abs_integral.hpp).
template <class S>
void integrateKinkedCriteria(const ChebyshevGrid& grid, const IntegrandValues<S>& f, const S& a,
                             const S& b, std::array<S, 4>& r, std::vector<S>& kinks) {
  const double orientation = valueOf(b) < valueOf(a) ? -1.0 : 1.0;
  const S half_length = 0.5 * orientation * (b - a);
  const Eigen::Matrix<S, Eigen::Dynamic, 1> power = f[kPower] * S(orientation);
  std::vector<S> roots;
  r[kCriterionCE] = half_length * integratePositivePart(grid, power, roots);
  r[kCriterionW] = S(0.0);
  for (int j = 0; j < 4; ++j)
    r[kCriterionW] += half_length * integrateAbs(grid, f[kJointPower + j], roots);
  std::sort(roots.begin(), roots.end(),
            [](const S& x, const S& y) { return valueOf(x) > valueOf(y); });
  for (const S& s : roots) kinks.push_back(a + 0.5 * (1.0 - s) * (b - a));
}

template <class S>
std::array<S, 4> integrateCriteria(const ChebyshevGrid& grid, const IntegrandValues<S>& f,
                                   const S& a, const S& b, std::vector<S>& kinks) {
  std::array<S, 4> r;
  integrateSmoothCriteria(grid, f, a, b, r);
  integrateKinkedCriteria(grid, f, a, b, r, kinks);
  return r;
}

// DS pieces: the times where the force-distribution branch changes, from the sign changes of
// its continuous switching functions between grid nodes, and the branch inside each piece. The
// criteria integrands are continuous there, so the switch times carry no derivative (the Leibniz
// terms cancel) and are plain doubles.
template <class S>
DsPieces dsPieces(EvalContext<S>& c, const Eigen::Matrix<S, Eigen::Dynamic, 1>& ts,
                  const std::vector<int>& branch,
                  const std::vector<std::array<double, 6>>& switching) {
  const auto phi = [&c](double t, int i) {
    return valueOf(dsSample(c.model, c.options, c.out.motion, S(t)).switching[i]);
  };
  std::vector<std::pair<double, int>> found;
  for (std::size_t k = 0; k + 1 < switching.size(); ++k)
    for (int i = 0; i < 6 && branch[k] != branch[k + 1]; ++i) {
      const double a = switching[k][i], b = switching[k + 1][i];
      if ((a < 0.0) == (b < 0.0)) continue;
      const auto fn = [&phi, i](double t) { return phi(t, i); };
      found.push_back({bracketedRoot(fn, valueOf(ts(k)), a, valueOf(ts(k + 1)), b), i});
    }
  std::sort(found.begin(), found.end());
  DsPieces pieces;
  const double h = 1e-7 * valueOf(c.out.motion.T_DS);
  for (const auto& [t, i] : found) {
    pieces.switch_times.push_back(t);
    pieces.switch_function.push_back(i);
    const double rate = (phi(t + h, i) - phi(t - h, i)) / (2.0 * h);
    pieces.switch_rate.push_back(std::isfinite(rate) ? rate : 0.0);
  }
  const double T = valueOf(c.out.motion.T_DS);
  for (std::size_t i = 0; i <= found.size(); ++i) {
    const double a = i == 0 ? 0.0 : found[i - 1].first;
    const double b = i == found.size() ? T : found[i].first;
    pieces.branches.push_back(dsSample(c.model, c.options, c.out.motion, S(0.5 * (a + b))).branch);
  }
  return pieces;
}

// A switch time with its parameter derivative from φ(t_s(p), p) = 0 (implicit function
// theorem, as (3.146)): one Newton step from the located root, on the AD scalar.
template <class S> S switchTimeWithDerivative(EvalContext<S>& c, const DsPieces& pieces, int j) {
  const double t = pieces.switch_times[j];
  if (pieces.switch_rate[j] == 0.0) return S(t);  // no usable rate: the switch stays put
  const S phi = dsSample(c.model, c.options, c.out.motion, S(t), pieces.branches[j])
                    .switching[pieces.switch_function[j]];
  return S(t) - phi / pieces.switch_rate[j];
}

// The DS level-5 entries of sample k of a piece, with the piece's branch, so that the
// constraints can be held between the DS nodes on smooth pieces (GaitEvaluation::ds_piece_g).
template <class S>
void recordPieceSample(EvalContext<S>& c, const std::vector<S>& ends, std::size_t piece, int k,
                       const PhaseSample<S>& s) {
  std::vector<std::vector<S>>& g = c.out.ds_piece_g;
  if (g.empty()) {
    g.assign(ends.size() + 1, std::vector<S>(c.layout.dsMotionSize()));
    c.out.ds_piece_bounds = {0.0};
    for (const S& t : ends) c.out.ds_piece_bounds.push_back(valueOf(t));
    c.out.ds_piece_bounds.push_back(valueOf(c.out.motion.T_DS));
  }
  std::vector<S>& v = g[piece];
  const int first = c.layout.dsMotionOffset();
  dsConstraintValues(c, k, s, [&c, &v, first](int group, int index, const S& value) {
    v[c.layout[group].offset + index - first] = value;
  });
}

template <class S>
std::array<S, 4> integrateDsPiecewise(EvalContext<S>& c, const DsPieces& pieces) {
  const GaitMotion<S>& mo = c.out.motion;
  const std::vector<double>& sw = pieces.switch_times;
  std::array<S, 4> total{S(0.0), S(0.0), S(0.0), S(0.0)};
  IntegrandValues<S> f = integrandValues<S>(c.piece_grid.size());
  std::vector<S> ends;
  for (std::size_t j = 0; j < sw.size(); ++j)
    ends.push_back(switchTimeWithDerivative(c, pieces, static_cast<int>(j)));
  for (std::size_t piece = 0; piece <= sw.size(); ++piece) {
    const S a = piece == 0 ? S(0.0) : ends[piece - 1];
    const S b = piece == sw.size() ? mo.T_DS : ends[piece];
    const auto ts = mappedNodes(c.piece_grid, a, b);
    for (int k = 0; k < c.piece_grid.size(); ++k) {
      const PhaseSample<S> s = dsSample(c.model, c.options, mo, S(ts(k)), pieces.branches[piece]);
      setIntegrands(c.model, s, k, S(1.0), f);
      if (c.record_pieces) recordPieceSample(c, ends, piece, k, s);
    }
    const std::array<S, 4> part = integrateCriteria(c.piece_grid, f, a, b, c.out.criteria_kinks);
    for (int i = 0; i < 4; ++i) total[i] += part[i];
  }
  return total;
}

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
    setIntegrands(c.model, s, k, S(1.0), ds_int);
  }
  c.out.ds_pieces = c.known_pieces ? *c.known_pieces : dsPieces(c, ts, branch, switching);
  return c.out.ds_pieces.switch_times.empty()
             ? integrateCriteria(c.ds_grid, ds_int, S(0.0), mo.T_DS, c.out.criteria_kinks)
             : integrateDsPiecewise(c, c.out.ds_pieces);
}

// The SS integrals of the criteria. W and C_E integrate |Γ*_j ω_j| and max(0, P) split at their
// roots, i.e. the integrands' interpolant between the nodes, which on the SS grid is accurate
// to ~10⁻⁹ only (a Clenshaw–Curtis sum, as for C_Γ, is exact far beyond its interpolant): they
// are sampled on the nested grid GaitGrids::ss_criteria (every r-th node an SS node, whose path
// point is reused) with Φ (3.14) integrated on that grid. C_Γ and C_frott keep the SS grid.
template <class S>
std::array<S, 4> ssCriteria(EvalContext<S>& c, const std::vector<SsPathPoint<S>>& pts,
                            const IntegrandValues<S>& ss_int) {
  const GaitMotion<S>& mo = c.out.motion;
  const S& a = mo.alpha_iSS;
  const S& b = mo.alpha_fSS;
  std::array<S, 4> r;
  integrateSmoothCriteria(c.ss_grid, ss_int, a, b, r);
  const ChebyshevGrid& fine = c.ss_criteria_grid;
  const int refinement = fine.degree() / c.ss_grid.degree();
  if (refinement == 1) {
    integrateKinkedCriteria(c.ss_grid, ss_int, a, b, r, c.out.criteria_kinks);
    return r;
  }
  const auto alphas = mappedNodes(fine, a, b);
  std::vector<SsPathPoint<S>> added;
  added.reserve(fine.size() - pts.size());
  for (int k = 0; k < fine.size(); ++k)
    if (k % refinement != 0) added.push_back(ssPathPoint(c.model, mo, S(alphas(k))));
  const auto point = [&](int k) -> const SsPathPoint<S>& {
    return k % refinement == 0 ? pts[k / refinement] : added[k - k / refinement - 1];
  };
  const double f_min = c.options.f_min;
  Eigen::Matrix<S, Eigen::Dynamic, 1> dphi(fine.size());
  for (int k = 0; k < fine.size(); ++k) dphi(k) = phiRate(point(k), f_min);
  const auto phi = cumulativeOverInterval(fine, dphi, a, b);
  IntegrandValues<S> f = integrandValues<S>(fine.size());
  for (int k = 0; k < fine.size(); ++k) {
    S ad, add;
    zeroDynamicsRates(point(k), phi(k), mo, f_min, ad, add);
    setIntegrands(c.model, ssSample(c.model, point(k), ad, add), k, ad, f);
  }
  integrateKinkedCriteria(fine, f, a, b, r, c.out.criteria_kinks);
  return r;
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
    phaseConstraintValues(c, kTorqueSS, kJointLimitsSS, k, s, layoutWriter(c, st));
    contactConstraintValues(c, kFrictionConeSS, kNormalForceSS, 0, 1, k, s.R1, layoutWriter(c, st));
    if (k > 0 && k < nss - 1) {  // (3.49) on the open interval (gap #16)
      const S x = s.foot2(0) / mo.d;
      c.set(kClearance, k - 1, -(s.foot2(1) - o.clearance_height * (1.0 - x * x)), st);
    }
    setIntegrands(c.model, s, k, ad, ss_int);  // dt = dα / α̇ (3.29)
  }
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
