#pragma once
// Levels 0–1 of a step evaluation: the boundary configurations from the parameters, their
// reach (3.36), (3.37), order (3.38) and tibia orientation (3.40), and, for a landing with an
// impact, the impact's constraints (gait/impact_landing.hpp).
#include <array>
#include <cmath>
#include <vector>

#include "gaitopt/gait/constraints/boundary_order.hpp"
#include "gaitopt/gait/constraints/impact_landing.hpp"
#include "gaitopt/gait/constraints/reach.hpp"
#include "gaitopt/gait/evaluation_context.hpp"
#include "gaitopt/gait/impact_landing.hpp"
#include "gaitopt/gait/leg_geometry.hpp"

namespace gaitopt {

// Hip-to-foot-2 vector with foot 2 on the ground at x = −d (corrected (3.18)).
template <class S>
Vector2<S> rearFootFromHip(const Model& m, const S& alpha, const S& delta1, const S& d) {
  const Vector2<S> f1 = foot1FromHip(m, alpha, delta1);
  return Vector2<S>(f1(0) - d, f1(1));
}

template <class S>
Vector5<S> dsConfiguration(const Model& m, const S& alpha, const S& delta1, const S& theta3,
                           const Vector2<S>& r) {
  const Vector2<S> leg2 = leg2InverseKinematics(m, alpha, delta1, r);
  return Vector5<S>(alpha, delta1, delta2FromTheta3(alpha, delta1, theta3), leg2(0), leg2(1));
}

}  // namespace gaitopt

namespace gaitopt::detail {

template <class S>
void setReach(EvalContext<S>& c, int max_group, const Vector2<S>& r, ConstraintState st) {
  const double L = c.model.robot.l4 + c.model.robot.l5;
  const std::array<S, 2> g = reachRows(S(r.squaredNorm()), L, c.options.reach_margin);
  c.set(max_group, 0, g[0], st);  // (3.36), (3.37)
  c.set(max_group + 1, 0, g[1], st);
}

// Touchdown with impact (gait/impact_landing.hpp): the pre-impact slopes are parameters, the
// impact's arrival, behaviour consistency and rate ratio are level-1 constraints, since the
// step's boundary conditions (the next phase's initial slopes) depend on them.
// When the touchdown configuration is out of reach (level 0 fails) the impact runs, as an
// extension, on the rear leg stretched or folded to the reach limit along the hip–foot line,
// so that the level-1 projection always has values.
template <class S> void impactLandingStage(EvalContext<S>& c, const Vector2<S>& r_iDS, bool ids_ok) {
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
  c.set(kImpactArrival, 0, impactArrivalRow(S(mo.landing.v2_minus(1))), st);  // (2.2)
  std::vector<S> g;
  landingConsistency(c.model, mo.landing, par.landing, g);
  for (std::size_t k = 0; k < g.size(); ++k) c.set(kImpactConsistency, static_cast<int>(k), g[k], st);
  c.set(kImpactRateRatio, 0, impactRateRatioRow(mo.landing.rate_ratio, c.options.kappa_min), st);
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
    c.set(kAlphaOrderDS, 0,
          alphaOrderDsRow(p(kAlphaIDS), p(kAlphaFDS), c.options.ds_alpha_range_min), D);
  c.set(kAlphaOrderSS, 0, alphaOrderSsRow(p(kAlphaFDS), mo.alpha_fSS, am), D);
  c.set(kTibiaFront, 0, tibiaFrontRow(p(kAlphaIDS), am), D);
  c.set(kTibiaRear, 0, tibiaRearRow(mo.alpha_fSS, am), D);
  if (par.landsWithImpact()) impactLandingStage(c, r_iDS, ids_ok);
  if (c.lowestViolated(1) >= 0) return false;

  mo.q_fDS = dsConfiguration(m, p(kAlphaFDS), p(kDelta1FDS), p(kTheta3FDS), r_fDS);
  mo.q_iSS = mo.q_fDS;
  const int mid = par.ss_points / 2;
  mo.q_ss_points[mid] = dsConfiguration(m, S(mo.q_ss_points[mid](0)), p(kDelta1Int),
                                        p(kTheta3Int), r_int);
  return true;
}

}  // namespace gaitopt::detail
