// DS time-optimal control of α (§4.2.1, §4.2.2.2): the path kinematics (4.3), (4.4), the exact
// LPs (4.14) against a brute-force scan of α̈ with every constraint of (4.2) evaluated from the
// plant's DS equations, the zone S_d (Theorem 1) and the law (4.1) reaching the cyclic curve.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>

#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/joint_friction.hpp"
#include "gaitopt/model/torque_envelope.hpp"
#include "gaitopt/sim/ds_convergence_zone.hpp"
#include "test_default_gait.hpp"

namespace gaitopt::test {
namespace {

double alphaIDS(const GaitMotion<double>& mo) { return mo.ds_alpha(0.0).value; }
double alphaFDS(const GaitMotion<double>& mo) { return mo.ds_alpha(mo.T_DS).value; }

// (4.2) at (q̈, R2x) from the plant's DS equations A q̈ + C + G = D_Γ Γ + D2ᵀ R2 solved for
// (Γ, R2z) directly, and Newton's equations for R1: the largest violation (≤ 0: all hold).
double worstViolation(const Model& m, const DsPathMotion& p, const DsLimits& l, double alphadd,
                      double r2x) {
  const Vec5 qdd = p.qdd_alphadd * alphadd + p.qdd_bias;
  const PinnedTerms<double> t = pinnedTerms(m, p.q, p.qd);
  Eigen::Matrix<double, 5, 5> K;
  K << m.D_Gamma, t.D2.row(1).transpose();
  const Vec5 x = K.partialPivLu().solve(Vec5(t.A * qdd + t.C + t.G - t.D2.row(0).transpose() * r2x));
  const Vec4 omega = jointSpeeds(p.qd);
  const Vec4 gamma_star = x.head<4>() + frictionTorque(m, omega, SignMode::Smooth);
  const Vec2 R2(r2x, x(4));
  const Vec2 acc = pinnedComAcceleration(m, p.q, p.qd, qdd);
  const Vec2 R1 = m.total_mass * Vec2(acc(0), acc(1) + m.gravity) - R2;
  double worst = -1e300;
  for (int j = 0; j < 4; ++j)
    worst = std::max(worst, std::abs(gamma_star(j)) -
                                torqueLimit(m.robot.envelope, omega(j), l.full_torque_envelope));
  for (const Vec2& R : {R1, R2})
    worst = std::max({worst, l.min_normal_force - R(1),
                      std::abs(R(0)) - l.friction_coefficient * R(1)});
  return worst;
}

// Whether some R2x satisfies (4.2) at α̈: the violation is convex in R2x, so a golden-section
// search of its minimum over a wide bracket decides (to round-off).
bool feasibleAt(const Model& m, const DsPathMotion& p, const DsLimits& l, double alphadd) {
  const auto v = [&](double r2x) { return worstViolation(m, p, l, alphadd, r2x); };
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = -1e4, hi = 1e4, a = hi - g * (hi - lo), b = lo + g * (hi - lo);
  double va = v(a), vb = v(b);
  for (int k = 0; k < 110; ++k) {
    if (va < vb) {
      hi = b, b = a, vb = va, a = hi - g * (hi - lo), va = v(a);
    } else {
      lo = a, a = b, va = vb, b = lo + g * (hi - lo), vb = v(b);
    }
  }
  return std::min(va, vb) <= 1e-11;
}

// Edge of the feasible α̈ interval between a feasible and an infeasible value, by bisection.
double edge(const Model& m, const DsPathMotion& p, const DsLimits& l, double in, double out) {
  while (std::abs(out - in) > 1e-11 * std::max(1.0, std::abs(in))) {
    const double mid = 0.5 * (in + out);
    (feasibleAt(m, p, l, mid) ? in : out) = mid;
  }
  return in;
}

}  // namespace

TEST_CASE("DS path: foot 2 stays on the ground, q̇ and q̈ are the path's derivatives (4.3), (4.4)",
          "[stability][ds_bounds]") {
  const DefaultGait f;
  const GaitMotion<double>& mo = f.evaluation.motion;
  const double alpha = 0.5 * (alphaIDS(mo) + alphaFDS(mo)), alphad = -0.9, alphadd = 3.0;
  const DsPathMotion p = dsPathMotion(f.model, mo, alpha, alphad);
  const PinnedTerms<double> t = pinnedTerms(f.model, p.q, p.qd);
  CHECK(t.foot2(0) == Approx(-mo.d).margin(1e-12));
  CHECK(t.foot2(1) == Approx(0.0).margin(1e-12));
  const Vec5 qdd = p.qdd_alphadd * alphadd + p.qdd_bias;
  CHECK((t.D2 * p.qd).norm() < 1e-12);
  CHECK((t.D2 * qdd + t.H2).norm() < 1e-10);  // (1.35)
  const double h = 1e-6;
  const Vec5 dq = (dsPathMotion(f.model, mo, alpha + h, alphad).q -
                   dsPathMotion(f.model, mo, alpha - h, alphad).q) / (2.0 * h);
  CHECK((dq * alphad - p.qd).norm() < 1e-8);
  // d q̇ / dt along (α̇, α̈): central difference over time h.
  const Vec5 qd_next = dsPathMotion(f.model, mo, alpha + h * alphad, alphad + h * alphadd).qd;
  const Vec5 qd_prev = dsPathMotion(f.model, mo, alpha - h * alphad, alphad - h * alphadd).qd;
  CHECK(((qd_next - qd_prev) / (2.0 * h) - qdd).norm() < 1e-6);
}

TEST_CASE("DS alpha-acceleration bounds: the LPs (4.14) equal a brute-force scan of alphadd",
          "[stability][ds_bounds]") {
  const DefaultGait f;
  const GaitMotion<double>& mo = f.evaluation.motion;
  const DsLimits l = dsLimitsOf(f.gait.options);
  const std::vector<double> fractions =
      lightTests() ? std::vector<double>{0.5} : std::vector<double>{0.1, 0.5, 0.9};
  int checked = 0;
  for (double u : fractions)
    for (double scale : {0.6, 1.0, 1.3}) {
      const double alpha = alphaFDS(mo) + u * (alphaIDS(mo) - alphaFDS(mo));
      const double alphad = scale * cyclicDsAlpha(mo, alpha).alphad;
      INFO("alpha " << alpha << ", alphad " << alphad);
      const DsPathMotion p = dsPathMotion(f.model, mo, alpha, alphad);
      const DsAccelerationBounds b = solveDsAccelerationLp(dsConstraintRows(f.model, p, l));
      // Scan α̈ for a feasible value, then the interval's edges by bisection.
      double inside = std::numeric_limits<double>::quiet_NaN();
      for (double a = -400.0; a <= 400.0 && std::isnan(inside); a += lightTests() ? 8.0 : 2.0)
        if (feasibleAt(f.model, p, l, a)) inside = a;
      REQUIRE(b.defined == !std::isnan(inside));
      if (!b.defined) continue;
      REQUIRE(std::isfinite(b.min));
      REQUIRE(std::isfinite(b.max));
      CHECK(b.min < b.max);
      const double lo = edge(f.model, p, l, inside, -1e4), hi = edge(f.model, p, l, inside, 1e4);
      CHECK(b.min == Approx(lo).margin(1e-9 * std::max(1.0, std::abs(lo))));
      CHECK(b.max == Approx(hi).margin(1e-9 * std::max(1.0, std::abs(hi))));
      // The optimal vertices satisfy every constraint.
      CHECK(worstViolation(f.model, p, l, b.min, b.r2x_at_min) <= 1e-8);
      CHECK(worstViolation(f.model, p, l, b.max, b.r2x_at_max) <= 1e-8);
      ++checked;
    }
  CHECK(checked >= 1);
}

TEST_CASE("DS alpha-acceleration LP: an empty polygon is reported undefined, an open side infinite",
          "[stability][ds_bounds]") {
  DsConstraintRows rows = DsConstraintRows::Zero();
  rows.col(2).setConstant(-1.0);  // 0 ≤ 1 everywhere
  rows.row(0) << 1.0, 0.0, -2.0;  // α̈ ≤ 2
  rows.row(1) << -1.0, 1.0, 0.0;  // R2x ≤ α̈
  rows.row(2) << 0.0, -1.0, -1.0;  // R2x ≥ −1 → α̈ ≥ −1
  DsAccelerationBounds b = solveDsAccelerationLp(rows);
  REQUIRE(b.defined);
  CHECK(b.min == Approx(-1.0).margin(1e-12));
  CHECK(b.max == Approx(2.0).margin(1e-12));
  rows.row(0) << 0.0, 0.0, -1.0;  // drop α̈ ≤ 2
  b = solveDsAccelerationLp(rows);
  CHECK(b.max == std::numeric_limits<double>::infinity());
  rows.row(3) << 1.0, 0.0, 5.0;  // α̈ ≤ −5 with α̈ ≥ −1: empty
  CHECK_FALSE(solveDsAccelerationLp(rows).defined);
  CHECK(std::string(dsConstraintName(12)) == "R2_cone_front");
}

TEST_CASE("S_d (Theorem 1): starts between the bound curves reach the DS end, others do not",
          "[stability][ds_bounds]") {
  const DefaultGait f;
  const GaitMotion<double>& mo = f.evaluation.motion;
  const DsLimits l = dsLimitsOf(f.gait.options);
  const double target = mo.ds_alpha(mo.T_DS).first, a0 = alphaIDS(mo);
  const DsConvergenceZone z = dsConvergenceZone(f.model, mo, l, target, 41);
  REQUIRE(z.braking.end == "alpha_iDS");
  const double fast = z.fastest(a0), slow = z.slowest(a0);
  INFO("fastest " << fast << ", slowest " << slow << " (" << z.speeding_up.end << ")");
  CHECK(fast < slow);
  CHECK(slow <= 0.0);
  // Both curves end on the target; braking makes the start faster, speeding up slower.
  CHECK(z.braking.alphad.front() == target);
  CHECK(fast < target);
  CHECK(slow > mo.ds_alpha(0.0).first - 1e-12);
  // The cycle lies in its own zone (Theorem 3 with the gait's own a(α̇_fDS) = α̇_c,iDS).
  CHECK(z.contains(a0, mo.ds_alpha(0.0).first));
  // Just outside the braking curve: reported outside, and the law (4.1) misses the cycle.
  const double outside = fast * 1.02;
  CHECK_FALSE(z.contains(a0, outside));
  const DsPhaseCurve miss = runTimeOptimalDs(f.model, mo, l, a0, outside, 41);
  CHECK(miss.end != "on_cycle");
  // Just inside: reported inside, and the law reaches the cyclic curve.
  const double inside = fast * 0.98;
  CHECK(z.contains(a0, inside));
  CHECK(runTimeOptimalDs(f.model, mo, l, a0, inside, 41).end == "on_cycle");
  // The slow side: rest is inside iff the speeding-up curve stops before α_iDS.
  CHECK(z.contains(a0, 0.0) == (z.speeding_up.end == "at_rest"));
  CHECK((runTimeOptimalDs(f.model, mo, l, a0, 0.0, 41).end == "on_cycle") ==
        (z.speeding_up.end == "at_rest"));
  CHECK_FALSE(z.contains(a0, 0.01));  // retrograde motion is outside (H2)
}

TEST_CASE("Time-optimal DS law (4.1) meets the cyclic curve and ends on it at alpha_fDS",
          "[stability][ds_bounds]") {
  const DefaultGait f;
  const GaitMotion<double>& mo = f.evaluation.motion;
  const DsLimits l = dsLimitsOf(f.gait.options);
  const double a0 = alphaIDS(mo), a1 = alphaFDS(mo), cycle_iDS = mo.ds_alpha(0.0).first;
  REQUIRE(a0 > a1);  // α decreases in DS (H2)
  const double cycle_fDS = mo.ds_alpha(mo.T_DS).first;
  const DsConvergenceZone z = dsConvergenceZone(f.model, mo, l, cycle_fDS, 41);
  // Halfway to the fastest start (too fast), the cycle itself, halfway to the slowest.
  for (double u : {-0.5, 0.0, 0.5}) {
    const double start = cycle_iDS + std::abs(u) * ((u < 0.0 ? z.fastest(a0) : z.slowest(a0)) - cycle_iDS);
    INFO("start alphad " << start);
    REQUIRE(z.contains(a0, start));
    const DsPhaseCurve c = runTimeOptimalDs(f.model, mo, l, a0, start, 61);
    REQUIRE(c.end == "on_cycle");
    CHECK(c.alpha.back() == Approx(a1).margin(1e-14));
    CHECK(c.end_alphad == Approx(cycle_fDS).epsilon(1e-10));
    // Before meeting the curve the state stays on the side it started from, and the bang
    // phase follows the bound: braking when too fast slows it (|α̇| falls as α falls).
    for (std::size_t k = 0; k < c.alpha.size(); ++k) {
      const double gap = c.alphad[k] - cyclicDsAlpha(mo, c.alpha[k]).alphad;
      if (u < 0.0) CHECK(gap <= 1e-9);
      if (u > 0.0) CHECK(gap >= -1e-9);
      if (u == 0.0) CHECK(std::abs(gap) <= 1e-12);
    }
    if (u < 0.0) CHECK(std::abs(c.alphad[1]) < std::abs(c.alphad[0]));
  }
}

}  // namespace gaitopt::test

namespace gaitopt::test {

TEST_CASE("Fig. 4.5 study: a (4.28) through the gait's own cycle, the cycle inside its zone",
          "[stability][ds_bounds]") {
  const DefaultGait f;
  const GaitMotion<double>& mo = f.evaluation.motion;
  const double cycle_fDS = mo.ds_alpha(mo.T_DS).first, cycle_iDS = mo.ds_alpha(0.0).first;
  // (4.28) at the cycle's α̇_fDS = α̇_iSS gives the gait's own DS start rate.
  CHECK(zeroDynamicsStepMap(mo, cycle_fDS) == Approx(cycle_iDS).epsilon(1e-9));
  // Faster SS start, faster touchdown; far too slow a start falls back in SS.
  CHECK(zeroDynamicsStepMap(mo, 1.1 * cycle_fDS) < cycle_iDS);
  CHECK(std::isnan(zeroDynamicsStepMap(mo, 0.0)));
  const DsZoneStudy s =
      studyDsZone(f.model, mo, dsLimitsOf(f.gait.options), {0.9 * cycle_fDS, cycle_fDS});
  REQUIRE(s.rows.size() == 2u);
  CHECK(s.cycle_in_zone == (s.cycle.fastest_iDS <= cycle_iDS && cycle_iDS <= s.cycle.slowest_iDS));
  CHECK(s.cycle_in_zone);
  CHECK(s.rows[1].fastest_iDS == s.cycle.fastest_iDS);
  CHECK(s.rows[1].cycle_exists);
  CHECK(s.existence_low <= cycle_fDS);
  CHECK(s.existence_high >= cycle_fDS);
  // Theorem 2's premise on the optimised cycle: its α̈_c within [α̈_min, α̈_max] up to the
  // optimiser's constraint tolerance between its collocation nodes.
  CHECK(s.cycle_braking_margin > -1e-3);
  CHECK(s.cycle_speeding_up_margin > -1e-3);
  // From rest the law (4.1) reaches the cycle iff rest is in the zone (Theorem 1).
  CHECK((s.from_rest.end == "on_cycle") == (s.cycle.slowest_iDS == 0.0));
}

}  // namespace gaitopt::test

#include "gaitopt/sim/hybrid_walk.hpp"
#include "gaitopt/sim/impact_touchdown.hpp"

namespace gaitopt::test {

TEST_CASE("Closed-loop time-optimal DS control brakes at the LP bound, then rides the cycle",
          "[stability][ds_bounds]") {
  const DefaultGait f;
  const GaitMotion<double>& mo = f.evaluation.motion;
  WalkRequest req;
  req.steps = 1;
  configureForGait(f.gait.options, req);
  req.ds_control = DsAlphaControl::TimeOptimal;
  req.dalphad0 = -0.03;  // faster than the cycle: touchdown too fast, (4.1) brakes
  req.sample_rate = lightTests() ? 2000.0 : 10000.0;
  const WalkResult r = simulateWalk(f.evaluation, f.model, f.model, req,
                                    gaitTouchdown(f.gait.options, "auto", req.friction_coefficient));
  INFO(r.message);
  REQUIRE(r.outcome == WalkOutcome::Completed);
  const DsLimits l{f.gait.options.friction_coefficient, req.min_normal_force,
                   f.gait.options.full_torque_envelope};
  int at_bound = 0, ds = 0;
  for (const WalkSample& s : r.samples) {
    if (s.single_support) continue;
    ++ds;
    const DsAccelerationBounds b = dsAccelerationBounds(f.model, mo, l, s.q(0), s.qd(0));
    REQUIRE(b.defined);
    const double gap = cyclicDsAlpha(mo, s.q(0)).alphad - s.qd(0);  // > 0: too fast
    INFO("alpha " << s.q(0) << ", alphadd " << s.qdd(0) << " in [" << b.min << ", " << b.max
                  << "], gap " << gap);
    CHECK(s.qdd(0) <= b.max + 1e-3 * std::abs(b.max));
    CHECK(gap >= -1e-9);  // never overshoots to the slow side
    if (gap * kTimeOptimalGain > b.max - cyclicDsAlpha(mo, s.q(0)).slope * s.qd(0)) {
      CHECK(s.qdd(0) == Approx(b.max).epsilon(1e-3));
      ++at_bound;
    }
  }
  CHECK(at_bound >= 1);
  CHECK(ds > at_bound);
  // Lift-off on the cycle: α̇_iSS of the gait.
  CHECK(r.qd_end(0) == Approx(mo.alphadot_iSS).epsilon(1e-6));
}

}  // namespace gaitopt::test
