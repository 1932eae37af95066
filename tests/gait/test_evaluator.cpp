// The gait evaluator (§3.3): continuity of the exported motion through the leg exchange and the
// cycle, the dynamics it claims to satisfy (zero dynamics in SS, Newton–Euler with the DS force
// distribution), the criterion against an independent time quadrature, exact gradients against
// finite differences, the constraint hierarchy and its saturations, and quadrature convergence.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"
#include "gaitopt/model/joint_friction.hpp"
#include "gaitopt/gait/leg_geometry.hpp"
#include "gaitopt/math/chebyshev_maxima.hpp"
#include "test_gait_support.hpp"
#include "test_gradient_check.hpp"

using namespace gaitopt;
using gaitopt::test::defaultGaitEvaluator;
using gaitopt::test::checkGradient;
using gaitopt::test::definedStep;
using gaitopt::test::GradientCheck;
using gaitopt::test::GradientOutput;

namespace {

void report(const char* what, double value) {
  std::printf("  [gait] %-56s %.3e\n", what, value);
}

// D_Γ (5×4) from its defining relation ω = D_Γᵀ q̇ (jointSpeeds), column by column of D_Γᵀ.
Eigen::Matrix<double, 5, 4> dGamma() {
  Eigen::Matrix<double, 5, 4> D;
  for (int i = 0; i < 5; ++i) D.row(i) = jointSpeeds(Vec5(Vec5::Unit(i))).transpose();
  return D;
}

// Index of the first DS row; every row before it is SS.
std::size_t firstDsRow(const std::vector<TrajectoryRow>& rows) {
  std::size_t k = 0;
  while (k < rows.size() && rows[k].phase == Phase::SingleSupport) ++k;
  return k;
}

double maxAbsDiff(const Vec5& a, const Vec5& b) { return (a - b).cwiseAbs().maxCoeff(); }

bool allComputedFinite(const GaitEvaluation<double>& e) {
  for (std::size_t k = 0; k < e.g.size(); ++k)
    if (e.state[k] != ConstraintState::NotComputed && !std::isfinite(e.g[k])) return false;
  return true;
}

bool criteriaFinite(const GaitEvaluation<double>& e) {
  for (double v : {e.C_Gamma, e.C_E, e.W, e.C_frott, e.T_SS, e.T_DS, e.speed, e.alphadot_fSS})
    if (!std::isfinite(v)) return false;
  return true;
}

// Largest value of the computed entries of one constraint group (−inf if none).
double groupMax(const GaitEvaluator& ev, const GaitEvaluation<double>& e, int group) {
  const ConstraintGroup& g = ev.layout()[group];
  double m = -HUGE_VAL;
  for (int k = g.offset; k < g.offset + g.count; ++k)
    if (e.state[k] != ConstraintState::NotComputed) m = std::max(m, e.g[k]);
  return m;
}

}  // namespace

TEST_CASE("the defined step is defined: levels 0-4 hold, level 5 fails", "[gait]") {
  const GaitEvaluator ev = defaultGaitEvaluator();
  const GaitEvaluation<double> e = ev.evaluate(definedStep());
  CHECK(e.failed_level == 5);
  CHECK(e.defined());
  CHECK(e.motion_computed);
  CHECK(criteriaFinite(e));
  CHECK(allComputedFinite(e));
  for (std::size_t k = 0; k < e.g.size(); ++k) {
    INFO("entry " << k << " level " << ev.layout().levelOf(static_cast<int>(k)));
    CHECK(e.state[k] == ConstraintState::Defined);
  }
  CHECK(e.T_SS > 0.0);
  CHECK(e.speed == Approx(e.step_length / (e.T_SS + e.T_DS)).epsilon(1e-14));
}

TEST_CASE("trajectory is continuous through the leg exchange and cyclic", "[gait]") {
  const GaitEvaluator ev = defaultGaitEvaluator();
  const Model& m = ev.model();
  const GaitParameters p = definedStep();
  const GaitEvaluation<double> e = ev.evaluate(p);
  REQUIRE(e.motion_computed);
  const std::vector<TrajectoryRow> rows = sampleTrajectory(ev, e, ev.options().sample_rate);
  const std::size_t ds0 = firstDsRow(rows);
  REQUIRE(ds0 >= 2);
  REQUIRE(ds0 + 2 <= rows.size());
  const TrajectoryRow& ss_first = rows.front();
  const TrajectoryRow& ss_last = rows[ds0 - 1];
  const TrajectoryRow& ds_first = rows[ds0];
  const TrajectoryRow& ds_last = rows.back();
  CHECK(ss_first.t == 0.0);
  CHECK(ss_last.t == Approx(e.T_SS).margin(1e-15));
  CHECK(ds_first.t == Approx(e.T_SS).margin(1e-15));
  CHECK(ds_last.t == Approx(e.T_SS + e.T_DS).margin(1e-14));

  SECTION("SS end -> DS start through the relabelling (3.22), (3.23)") {
    const double dq = maxAbsDiff(exchangeLegs(ss_last.q), ds_first.q);
    const double dqd = maxAbsDiff(exchangeLegVelocities(ss_last.qd), ds_first.qd);
    report("SS->DS exchange: max |q| difference", dq);
    report("SS->DS exchange: max |qd| difference", dqd);
    CHECK(dq < 1e-9);
    CHECK(dqd < 1e-9);
    // The DS start is the parameterised configuration.
    CHECK(ds_first.q(0) == Approx(p(kAlphaIDS)).margin(1e-12));
    CHECK(ds_first.q(1) == Approx(p(kDelta1IDS)).margin(1e-12));
  }

  SECTION("DS end -> SS start, same labels (3.21): the step is cyclic") {
    const double dq = maxAbsDiff(ds_last.q, ss_first.q);
    const double dqd = maxAbsDiff(ds_last.qd, ss_first.qd);
    report("DS end -> SS start: max |q| difference", dq);
    report("DS end -> SS start: max |qd| difference", dqd);
    CHECK(dq < 1e-9);
    CHECK(dqd < 1e-9);
    CHECK(ss_first.q(0) == Approx(p(kAlphaFDS)).margin(1e-12));
    CHECK(ss_first.qd(0) == Approx(p(kAlphadotISS)).margin(1e-12));  // not saturated here
  }

  SECTION("rear foot fixed at (-d, 0) in DS, swing foot at rest at both SS ends") {
    double pos = 0.0, vel = 0.0;
    for (std::size_t k = ds0; k < rows.size(); ++k) {
      const PinnedTerms<double> t = pinnedTerms(m, rows[k].q, rows[k].qd);
      pos = std::max(pos, (t.foot2 - Vec2(-p(kStepLength), 0.0)).cwiseAbs().maxCoeff());
      pos = std::max(pos, (rows[k].foot2 - Vec2(-p(kStepLength), 0.0)).cwiseAbs().maxCoeff());
      vel = std::max(vel, (t.D2 * rows[k].qd).cwiseAbs().maxCoeff());
    }
    report("DS rows: max |foot2 - (-d, 0)|", pos);
    report("DS rows: max |D2 qd|", vel);
    CHECK(pos < 1e-12);
    CHECK(vel < 1e-12);
    for (const TrajectoryRow* r : {&ss_first, &ss_last}) {
      const PinnedTerms<double> t = pinnedTerms(m, r->q, r->qd);
      const double v = (t.D2 * r->qd).cwiseAbs().maxCoeff();
      INFO("SS row at t = " << r->t);
      CHECK(v < 1e-9);
      CHECK(t.foot2(1) == Approx(0.0).margin(1e-9));  // on the ground at lift-off/touchdown
    }
    CHECK(pinnedTerms(m, ss_first.q, ss_first.qd).foot2(0) ==
          Approx(-p(kStepLength)).margin(1e-9));
    CHECK(pinnedTerms(m, ss_last.q, ss_last.qd).foot2(0) == Approx(p(kStepLength)).margin(1e-9));
  }
}

TEST_CASE("SS rows satisfy the zero dynamics: no moment at the point foot", "[gait]") {
  const GaitEvaluator ev = defaultGaitEvaluator();
  const Model& m = ev.model();
  const GaitEvaluation<double> e = ev.evaluate(definedStep());
  REQUIRE(e.motion_computed);
  const std::vector<TrajectoryRow> rows = sampleTrajectory(ev, e, ev.options().sample_rate);
  const std::size_t ds0 = firstDsRow(rows);
  REQUIRE(ds0 > 100);
  double worst_residual = 0.0, worst_gamma = 0.0;
  for (std::size_t k = 0; k < ds0; ++k) {
    const TrajectoryRow& r = rows[k];
    const SingleSupportInverseDynamics<double> id =
        inverseDynamicsSS(m, r.q, r.qd, r.qdd, SignMode::Smooth);
    const double G1 = pinnedTerms(m, r.q, r.qd).G(0);
    const double residual = std::abs(id.alpha_row_residual) / (std::abs(G1) + 1.0);
    const double gamma = (id.gamma_star - r.gamma_star).cwiseAbs().maxCoeff() /
                         (1.0 + r.gamma_star.cwiseAbs().maxCoeff());
    worst_residual = std::max(worst_residual, residual);
    worst_gamma = std::max(worst_gamma, gamma);
    INFO("SS row " << k << " t = " << r.t);
    CHECK(residual < 1e-8);
    CHECK(gamma < 1e-9);
    // Foot-1 reaction: the same Newton equations.
    CHECK((id.R1 - r.R1).cwiseAbs().maxCoeff() < 1e-9 * (1.0 + r.R1.cwiseAbs().maxCoeff()));
    CHECK(r.R2.norm() == 0.0);
  }
  report("SS: max |alpha-row residual| / (|G1| + 1)", worst_residual);
  report("SS: max |Gamma*_id - Gamma*_row| / (1 + |Gamma*|)", worst_gamma);
}

TEST_CASE("DS reactions and torques satisfy the pinned equations (1.32), (1.36)", "[gait]") {
  const GaitEvaluator ev = defaultGaitEvaluator();
  const Model& m = ev.model();
  const GaitEvaluation<double> e = ev.evaluate(definedStep());
  REQUIRE(e.motion_computed);
  const std::vector<TrajectoryRow> rows = sampleTrajectory(ev, e, ev.options().sample_rate);
  const std::size_t ds0 = firstDsRow(rows);
  REQUIRE(rows.size() - ds0 > 50);
  const Eigen::Matrix<double, 5, 4> DG = dGamma();
  const double M = m.total_mass;
  double worst_newton = 0.0, worst_alpha = 0.0, worst_rows = 0.0;
  for (std::size_t k = ds0; k < rows.size(); ++k) {
    const TrajectoryRow& r = rows[k];
    INFO("DS row " << k << " t = " << r.t);
    // Whole-body Newton equations.
    const Vec2 acc = pinnedComAcceleration(m, r.q, r.qd, r.qdd);
    const Vec2 newton(M * acc(0), M * (acc(1) + m.gravity));
    const double newton_err = (r.R1 + r.R2 - newton).cwiseAbs().maxCoeff() /
                              (1.0 + r.R1.cwiseAbs().maxCoeff() + r.R2.cwiseAbs().maxCoeff());
    worst_newton = std::max(worst_newton, newton_err);
    CHECK(newton_err < 1e-9);
    // Lagrange equations with foot 2 closed: A q̈ + C + G = D_Γ Γ + D2ᵀ R2.
    const PinnedTerms<double> t = pinnedTerms(m, r.q, r.qd);
    const Vec5 inertial = t.A * r.qdd;
    const Vec5 tau = inertial + t.C + t.G;
    const Vec4 gamma = r.gamma_star - frictionTorque(m, jointSpeeds(r.qd), SignMode::Smooth);
    const Vec5 contact = t.D2.transpose() * r.R2;
    const Vec5 rhs = DG * gamma + contact;
    CHECK(rhs(0) == contact(0));  // D_Γ has an empty α-row: the feet carry the whole moment
    for (int i = 0; i < 5; ++i) {
      const double scale = 1.0 + std::abs(inertial(i)) + std::abs(t.C(i)) + std::abs(t.G(i)) +
                           std::abs(contact(i));
      const double err = std::abs(tau(i) - rhs(i)) / scale;
      INFO("row " << i << ": tau = " << tau(i) << ", rhs = " << rhs(i));
      CHECK(err < 1e-8);
      (i == 0 ? worst_alpha : worst_rows) = std::max(i == 0 ? worst_alpha : worst_rows, err);
    }
  }
  report("DS: max Newton residual (relative)", worst_newton);
  report("DS: max alpha-row residual tau1 - (D2^T R2)_1 (relative)", worst_alpha);
  report("DS: max rows 2-5 residual (relative)", worst_rows);
}

TEST_CASE("C_Gamma equals the time integral over the exported trajectory", "[gait]") {
  const GaitEvaluator ev = defaultGaitEvaluator();
  const GaitEvaluation<double> e = ev.evaluate(definedStep());
  REQUIRE(e.motion_computed);
  const std::vector<TrajectoryRow> rows = sampleTrajectory(ev, e, 50000.0);
  const std::size_t ds0 = firstDsRow(rows);
  REQUIRE(ds0 > 1000);
  REQUIRE(rows.size() - ds0 > 1000);
  for (std::size_t k = ds0; k < rows.size(); ++k) REQUIRE(rows[k].phase == Phase::DoubleSupport);
  CHECK(rows[ds0 - 1].t == e.T_SS);
  CHECK(rows.back().t == Approx(e.T_SS + e.T_DS).epsilon(1e-15));
  // Trapezoid rule per phase; each phase is closed by its exact end row.
  const auto trapezoid = [&rows](std::size_t begin, std::size_t end) {
    double sum = 0.0;
    for (std::size_t k = begin + 1; k < end; ++k) {
      REQUIRE(rows[k].t > rows[k - 1].t);
      sum += 0.5 * (rows[k].t - rows[k - 1].t) *
             (rows[k].gamma_star.squaredNorm() + rows[k - 1].gamma_star.squaredNorm());
    }
    return sum;
  };
  const double c_ss = trapezoid(0, ds0), c_ds = trapezoid(ds0, rows.size());
  const double c = (c_ss + c_ds) / e.step_length;
  const double rel = std::abs(c - e.C_Gamma) / e.C_Gamma;
  report("C_Gamma (spectral, alpha-integration)", e.C_Gamma);
  report("C_Gamma: |trapezoid 50 kHz - spectral| / spectral", rel);
  CHECK(rel < 1e-6);
}

namespace {

std::string withoutIndex(const std::string& name) { return name.substr(0, name.find('[')); }

}  // namespace

TEST_CASE("exact gradients of T_SS, speed and the constraints equal finite differences",
          "[gait][derivatives]") {
  const GaitEvaluator ev = defaultGaitEvaluator();
  const GaitParameters p = definedStep();
  const GaitGradient grad = ev.evaluateWithGradient(p);
  const GaitEvaluation<double>& e0 = grad.value;
  REQUIRE(e0.defined());
  REQUIRE(e0.motion_computed);
  CHECK(e0.T_SS == ev.evaluate(p).T_SS);  // the gradient call returns the plain values

  std::vector<GradientOutput> outputs = {
      {"T_SS", [](const GaitEvaluation<double>& e) { return e.T_SS; }, grad.dT_SS},
      {"speed", [](const GaitEvaluation<double>& e) { return e.speed; }, grad.dspeed},
  };
  int defined_entries = 0;
  for (const ConstraintGroup& g : ev.layout().groups())
    for (int k = g.offset; k < g.offset + g.count; ++k) {
      if (e0.state[k] != ConstraintState::Defined) continue;
      ++defined_entries;
      outputs.push_back({g.name + "[" + std::to_string(k - g.offset) + "]",
                         [k](const GaitEvaluation<double>& e) { return e.g[k]; },
                         grad.dg.row(k).transpose()});
    }
  REQUIRE(defined_entries == ev.layout().size());
  const GradientCheck r = checkGradient(ev, p, outputs, withoutIndex);
  std::printf("  [gait] gradient of T_SS, speed, %d constraints: %d entries checked, %d skipped "
              "(kinks), max err %.3e at %s\n",
              defined_entries, r.checked, r.skipped, r.worst, r.worst_what.c_str());
  for (const auto& [name, count] : r.skipped_by_output)
    std::printf("  [gait]   skipped in %-28s %d\n", name.c_str(), count);
  INFO(r.failures);
  CHECK(r.failed == 0);
  CHECK(r.skipped_by_output.count("T_SS") == 0);
  CHECK(r.skipped_by_output.count("speed") == 0);
  CHECK(r.checked > defined_entries * kNumGaitParameters * 9 / 10);
  CHECK(static_cast<double>(r.skipped) < 0.02 * static_cast<double>(r.checked + r.skipped));
}

TEST_CASE("exact gradients of the criteria equal finite differences", "[gait][derivatives]") {
  const GaitEvaluator ev = defaultGaitEvaluator();
  const GaitParameters p = definedStep();
  const GaitGradient grad = ev.evaluateWithGradient(p);
  REQUIRE(grad.value.defined());
  const std::vector<GradientOutput> outputs = {
      {"C_Gamma", [](const GaitEvaluation<double>& e) { return e.C_Gamma; }, grad.dC_Gamma},
      {"C_E", [](const GaitEvaluation<double>& e) { return e.C_E; }, grad.dC_E},
      {"W", [](const GaitEvaluation<double>& e) { return e.W; }, grad.dW},
      {"C_frott", [](const GaitEvaluation<double>& e) { return e.C_frott; }, grad.dC_frott},
  };
  const GradientCheck r = checkGradient(ev, p, outputs, withoutIndex);
  std::printf("  [gait] gradient of the criteria: %d entries checked, %d skipped (kinks), max "
              "err %.3e at %s\n",
              r.checked, r.skipped, r.worst, r.worst_what.c_str());
  for (const auto& [name, err] : r.worst_by_output)
    std::printf("  [gait]   max err %-10s %.3e\n", name.c_str(), err);
  INFO(r.failures);
  CHECK(r.failed == 0);
  CHECK(r.skipped == 0);
}

TEST_CASE("each hierarchy level made to fail reports that level with finite values", "[gait]") {
  const GaitEvaluator ev = defaultGaitEvaluator();
  const ConstraintLayout& layout = ev.layout();
  struct Case {
    const char* what;
    int level;
    int param;
    double value;
    int failing_group;  // a group of that level that must be violated
  };
  const Case cases[] = {
      {"d = 2.0: hip-foot distance too long", 0, kStepLength, 2.0, kReachMaxIDS},
      {"alpha_fDS = 0 > alpha_iDS", 1, kAlphaFDS, 0.0, kAlphaOrderDS},
      // Found by scanning delta1_int, theta3_int and the four SS slopes: bending the
      // intermediate knee by 0.2 rad makes f(α) = A1 q* drop below f_min inside the SS.
      {"delta1_int + 0.2: f below f_min", 2, kDelta1Int, -2.245513, kFPositive},
      {"alphadot_iSS = -0.01: too slow to pass over the foot", 3, kAlphadotISS, -0.01,
       kNoFallBack},
      {"alphadot_iSS = +0.3: walking backwards", 3, kAlphadotISS, 0.3, kAlphadotNegative},
      {"T_DS = 1.0: non-monotone DS alpha leaves the reachable range", 4, kTDS, 1.0,
       kDsReachMax},
  };
  for (const Case& c : cases) {
    GaitParameters p = definedStep();
    p(c.param) = c.value;
    const GaitEvaluation<double> e = ev.evaluate(p);
    INFO(c.what);
    std::printf("  [gait] level %d case %-58s failed_level %d, worst %s = %.3e\n", c.level,
                c.what, e.failed_level, layout[c.failing_group].name.c_str(),
                groupMax(ev, e, c.failing_group));
    CHECK(e.failed_level == c.level);
    CHECK_FALSE(e.defined());
    CHECK(allComputedFinite(e));
    CHECK(criteriaFinite(e));
    CHECK(groupMax(ev, e, c.failing_group) > 0.0);
    for (int k = 0; k < layout.size(); ++k) {
      if (layout.levelOf(k) > c.level) continue;
      INFO("entry " << k << " level " << layout.levelOf(k));
      CHECK(e.state[k] == ConstraintState::Defined);  // levels up to the failing one are exact
      if (layout.levelOf(k) < c.level) CHECK(e.g[k] <= 0.0);
    }
    if (c.level >= 2) CHECK(e.T_SS > 0.0);
  }
}

TEST_CASE("the alphadot_iSS saturation (3.56) lets the SS pass over the foot", "[gait]") {
  const GaitEvaluator ev = defaultGaitEvaluator();
  const Model& m = ev.model();
  const GaitOptions& o = ev.options();
  GaitParameters p = definedStep();
  p(kAlphadotISS) = -0.01;
  const GaitEvaluation<double> e = ev.evaluate(p);
  REQUIRE(e.failed_level == 3);
  const GaitMotion<double>& mo = e.motion;
  // Unsaturated minimum recomputed from the SS path: f(α_iSS) = A1 q* and Φ_min.
  Vec5 q, qs;
  q(0) = mo.alpha_iSS;
  qs(0) = 1.0;
  for (int j = 0; j < 4; ++j) {
    const PolyValue<double> v = mo.ss_path[j](mo.alpha_iSS);
    q(j + 1) = v.value;
    qs(j + 1) = v.first;
  }
  const double f_i = std::max(pinnedTerms(m, q, qs).A.row(0).dot(qs), o.f_min);
  CHECK(f_i == Approx(mo.f_iSS).epsilon(1e-12));
  // min Φ over the whole SS, between the nodes too.
  const double phi_min = interpolantMinimum(ev.ssGrid(), mo.ss_phi);
  CHECK(phi_min <= mo.ss_phi.minCoeff());
  REQUIRE(phi_min < 0.0);  // the CoM must be carried over the stance foot
  const double a_min = -std::sqrt(-phi_min) / f_i;
  report("level 3: unsaturated minimum alphadot_iSS", a_min);
  report("level 3: saturated alphadot_iSS", mo.alphadot_iSS);
  CHECK(p(kAlphadotISS) > a_min);  // the given value falls back
  CHECK(mo.alphadot_iSS <= a_min - o.alphadot_margin + 1e-12);
  CHECK(mo.alphadot_iSS == Approx(a_min - o.alphadot_margin).epsilon(1e-12));
  // σ² = Φ + f_i² α̇_i² stays at least (f_i ε)² at every SS node.
  const double sigma2_min = phi_min + f_i * f_i * mo.alphadot_iSS * mo.alphadot_iSS;
  CHECK(sigma2_min >= (1.0 - 1e-9) * std::pow(f_i * o.alphadot_margin, 2));
  CHECK(std::isfinite(e.T_SS));
  CHECK(e.T_SS > 0.0);
  CHECK(e.T_SS == Approx(mo.ss_time(mo.ss_time.size() - 1)).epsilon(1e-15));
  CHECK(e.alphadot_fSS < 0.0);
}

TEST_CASE("C_Gamma has converged with the default quadrature", "[gait]") {
  const GaitParameters p = definedStep();
  const GaitEvaluation<double> coarse = defaultGaitEvaluator().evaluate(p);
  GaitOptions fine_options = test::viscousOptions();
  fine_options.ss_nodes = 96;
  fine_options.ds_nodes = 48;
  const GaitEvaluation<double> fine = defaultGaitEvaluator(fine_options).evaluate(p);
  REQUIRE(coarse.motion_computed);
  REQUIRE(fine.motion_computed);
  const double rel = std::abs(coarse.C_Gamma - fine.C_Gamma) / std::abs(fine.C_Gamma);
  report("C_Gamma: |32/16 nodes - 96/48 nodes| / fine", rel);
  report("T_SS: |32/16 nodes - 96/48 nodes| / fine", std::abs(coarse.T_SS - fine.T_SS) / fine.T_SS);
  // Smooth integrand (Γ*ᵀω): spectral too. C_E and W, split at their kinks, are asserted against
  // a refined evaluation in test_criteria_kinks.cpp; here their differences are reported only.
  const double rel_frott = std::abs(coarse.C_frott - fine.C_frott) / std::abs(fine.C_frott);
  report("C_frott: |32/16 nodes - 96/48 nodes| / fine", rel_frott);
  report("C_E (not asserted): |32/16 nodes - 96/48 nodes| / fine",
         std::abs(coarse.C_E - fine.C_E) / std::abs(fine.C_E));
  report("W (not asserted): |32/16 nodes - 96/48 nodes| / fine",
         std::abs(coarse.W - fine.W) / std::abs(fine.W));
  CHECK(rel < 1e-6);
  CHECK(rel_frott < 1e-6);
  CHECK(coarse.T_SS == Approx(fine.T_SS).epsilon(1e-9));
}

TEST_CASE("DS distributions minimise their own criterion pointwise", "[gait]") {
  // Same motion, only R2x differs in DS: at every DS sample the energy rule (3.71)–(3.75)
  // gives no larger electrical power max(0, P) than the torque rule (3.68)–(3.70), and the
  // torque rule no larger Γ*ᵀΓ*.
  GaitOptions energy = test::viscousOptions();
  energy.ds_distribution = DsDistribution::Energy;
  const GaitEvaluator et = test::defaultGaitEvaluator(), ee = test::defaultGaitEvaluator(energy);
  const GaitEvaluation<double> t = et.evaluate(test::optimalStep());
  const GaitEvaluation<double> e = ee.evaluate(test::optimalStep());
  REQUIRE(t.motion_computed);
  REQUIRE(e.motion_computed);
  CHECK(e.T_SS == t.T_SS);
  const std::vector<TrajectoryRow> rt = sampleTrajectory(et, t, 2000.0);
  const std::vector<TrajectoryRow> re = sampleTrajectory(ee, e, 2000.0);
  REQUIRE(rt.size() == re.size());
  const double k = jouleCoefficient(et.model());
  const auto power = [k](const TrajectoryRow& r) {
    const Vec4 w = jointSpeeds(Vec5(r.qd));
    return std::max(0.0, w.dot(r.gamma_star) + k * r.gamma_star.squaredNorm());
  };
  int ds_rows = 0, differing = 0;
  for (std::size_t i = 0; i < rt.size(); ++i) {
    if (rt[i].phase != Phase::DoubleSupport) continue;
    ++ds_rows;
    CHECK(power(re[i]) <= power(rt[i]) + 1e-9);
    CHECK(rt[i].gamma_star.squaredNorm() <= re[i].gamma_star.squaredNorm() + 1e-9);
    if (std::abs(rt[i].R2(0) - re[i].R2(0)) > 1e-6) ++differing;
  }
  CHECK(ds_rows > 10);
  CHECK(differing > 0);  // the two rules genuinely differ on this step
}

TEST_CASE("a motion that overflows is undefined at level 4, never NaN", "[gait]") {
  // A DS with 1e-3 rad of α range (found by a projection onto levels 0–4): its polynomials'
  // slopes reach 1e18 and the DS force split overflows. With the DS range margin switched off
  // the evaluator must still report no NaN.
  GaitParameters p(kNumGaitParameters);
  p << -0.019252834250073153, -2.5942644747345804, 1.5208076184025092, 0.34995961135393439,
      -0.02025482964101576, -2.4946304373232517, 1.5208063294147436, -2.4455184279386502,
      1.5207864380756257, -1.4437546173990962e-06, 0.059999795817441332, -1.1250027541370575,
      0.29945717215519196, 0.30018556938440627, 0.30024228850281709, 0.29982065456277085,
      0.11999763446337594;
  GaitOptions no_margin = test::viscousOptions();
  no_margin.ds_alpha_range_min = 0.0;
  const GaitEvaluator ev = test::defaultGaitEvaluator(no_margin);
  const GaitEvaluation<double> e = ev.evaluate(p);
  CHECK(e.numerically_undefined);
  CHECK(e.failed_level == 4);
  CHECK_FALSE(e.defined());
  CHECK_FALSE(e.motion_computed);
  for (std::size_t k = 0; k < e.g.size(); ++k) CHECK(std::isfinite(e.g[k]));
  CHECK(std::isfinite(e.C_Gamma));
  // With the default margin the same step fails the DS range condition (level 1) instead.
  CHECK(test::defaultGaitEvaluator().evaluate(p).failed_level == 1);
}
