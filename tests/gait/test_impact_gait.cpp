// Gaits landing with an impact (gait/impact_landing.hpp): exact gradients through the impact,
// cyclicity through the impact and the leg exchange, the energy balance of the cycle, the
// consistency constraint against an independent enumeration of the impact behaviours, the
// gait files, the default (zero-velocity) landing left as it was, and the touchdown at a
// minimum foot speed (gait/constraints/touchdown_speed.hpp).
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/impact_landing.hpp"
#include "gaitopt/gait/constraint_summary.hpp"
#include "gaitopt/io/summary_file.hpp"
#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/gait/feasibility.hpp"
#include "gaitopt/model/chain_kinematics.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "test_default_gait.hpp"
#include "test_files.hpp"
#include "test_gait_support.hpp"
#include "test_gradient_check.hpp"

using namespace gaitopt;
using gaitopt::test::checkGradient;
using gaitopt::test::GradientOutput;

namespace {

GaitOptions impactOptions(Landing landing) {
  GaitOptions o;
  o.parameterisation.landing = landing;
  return o;
}

GaitEvaluator chevallereauEvaluator(const GaitOptions& o) {
  return GaitEvaluator(test::robotFile("rabbit_chevallereau_aoustin"), o);
}

GaitOptions touchdownOptions(double v_min) {
  GaitOptions o = impactOptions(Landing::ImpactSingleSupport);
  o.touchdown_speed_min = v_min;
  return o;
}

// A defined step of the C&A robot landing with impact, then single support, at 0.75 m/s (the
// entries α_fDS … δ2*_iSS and T_DS are not read by this gait family).
GaitParameters singleSupportImpactStep() {
  GaitParameters p(kNumGaitParameters + 2);
  p << 0.05486164223, -2.749027249, 1.371980514, 0.43, -0.1363070094, -2.453762604,
      1.596719911, -2.961025259, 1.330439872, -0.09077827436, 0.07462916231, -1.077480138,
      -0.1298147577, 0.08765845745, 0.126106956, 1.913485596, 0.1348345692, 0.3351113543,
      4.333204436;
  return p;
}

std::string withoutIndex(const std::string& name) { return name.substr(0, name.find('[')); }

Vec5 pinnedFromFloating(const Vector7<double>& Xd) { return Xd.head<5>(); }

// Vertical velocity of the swing foot at the end of the single support, from the sampled
// motion q, q̇ and the pinned chain's foot-2 Jacobian (not from the landing's impact system).
double swingFootVz(const GaitEvaluator& ev, const GaitEvaluation<double>& e) {
  const TrajectoryRow r = sampleTrajectoryAt(ev, e, Phase::SingleSupport, e.T_SS);
  const Model& m = ev.model();
  return (chainPointJacobian(m, m.pinned.foot2, chainState(m, r.q, r.qd)) * r.qd)(1);
}

TEST_CASE("impact landing: the step is defined and its impact unique", "[gait][impact_gait]") {
  const GaitEvaluator ev = chevallereauEvaluator(impactOptions(Landing::ImpactSingleSupport));
  const GaitEvaluation<double> e = ev.evaluate(singleSupportImpactStep());
  REQUIRE(e.defined());
  REQUIRE(e.motion_computed);
  CHECK(e.T_DS == 0.0);
  CHECK(e.speed == Approx(e.step_length / e.T_SS).epsilon(1e-14));
  const LandingReport r = landingReport(e.motion.landing, Landing::ImpactSingleSupport,
                                        e.alphadot_fSS);
  const LandingSolutions all = landingSolutions(ev.model(), r, ev.options().friction_coefficient);
  CHECK(all.status == "unique");
  CHECK(all.required_found);
  CHECK(r.impulse1.norm() == 0.0);  // foot 1 lifts: no impulse (2.5)
  CHECK(r.impulse2(1) > 0.0);
  CHECK(std::abs(r.impulse2(0)) < ev.options().friction_coefficient * r.impulse2(1));
  CHECK(r.v2_minus(1) < 0.0);
  CHECK(r.energy_loss > 0.0);
}

// Every computed output of the evaluation at p against central differences.
test::GradientCheck checkImpactGradient(const GaitEvaluator& ev, const GaitParameters& p) {
  const GaitGradient grad = ev.evaluateWithGradient(p);
  const GaitEvaluation<double>& e0 = grad.value;
  REQUIRE(e0.failed_level != 0);
  REQUIRE(e0.failed_level != 1);
  std::vector<GradientOutput> outputs = {
      {"T_SS", [](const GaitEvaluation<double>& e) { return e.T_SS; }, grad.dT_SS},
      {"speed", [](const GaitEvaluation<double>& e) { return e.speed; }, grad.dspeed},
  };
  if (e0.motion_computed) {
    outputs.push_back(
        {"C_Gamma", [](const GaitEvaluation<double>& e) { return e.C_Gamma; }, grad.dC_Gamma});
    outputs.push_back({"C_E", [](const GaitEvaluation<double>& e) { return e.C_E; }, grad.dC_E});
    outputs.push_back({"W", [](const GaitEvaluation<double>& e) { return e.W; }, grad.dW});
  }
  for (const ConstraintGroup& g : ev.layout().groups())
    for (int k = g.offset; k < g.offset + g.count; ++k) {
      if (e0.state[k] == ConstraintState::NotComputed) continue;
      outputs.push_back({g.name + "[" + std::to_string(k - g.offset) + "]",
                         [k](const GaitEvaluation<double>& e) { return e.g[k]; },
                         grad.dg.row(k).transpose()});
    }
  const test::GradientCheck r = checkGradient(ev, p, outputs, withoutIndex);
  std::printf("  [impact_gait] %s: %d entries checked, %d skipped (kinks), max err %.3e at %s\n",
              ev.options().parameterisation.label().c_str(), r.checked, r.skipped, r.worst,
              r.worst_what.c_str());
  for (const auto& [name, count] : r.skipped_by_output)
    std::printf("  [impact_gait]   skipped in %-28s %d\n", name.c_str(), count);
  INFO(r.failures);
  CHECK(r.failed == 0);
  for (const char* name :
       {"T_SS", "speed", "impact_consistency", "impact_arrival", "impact_rate_ratio"}) {
    CHECK(r.skipped_by_output.count(name) == 0);
    CHECK(r.worst_by_output.count(name) == 1);
  }
  CHECK(static_cast<double>(r.skipped) < 0.02 * static_cast<double>(r.checked + r.skipped));
  return r;
}

}  // namespace

TEST_CASE("impact landing, then single support: exact gradients equal finite differences",
          "[gait][impact_gait][derivatives]") {
  const GaitEvaluator ev = chevallereauEvaluator(impactOptions(Landing::ImpactSingleSupport));
  REQUIRE(ev.evaluate(singleSupportImpactStep()).defined());
  const test::GradientCheck r = checkImpactGradient(ev, singleSupportImpactStep());
  for (const char* name : {"C_Gamma", "impact_orbit", "alphadot_iSS_negative", "no_fall_back"})
    CHECK(r.worst_by_output.count(name) == 1);
}

TEST_CASE("impact landing, then double support: exact gradients equal finite differences",
          "[gait][impact_gait][derivatives]") {
  // A step of the default robot (a best point of the optimiser) whose levels 0-3 hold (the impact's stick-stick consistency
  // among them) and whose DS, started with the post-impact velocity, is computed up to its
  // reach constraints (level 4).
  GaitParameters p(kNumGaitParameters + 2);
  p << 1.199979932, -2.9220025, 0.5708285135, 0.8112155845, 1.021046713, -2.594685303, 2.2081886,
      -2.357620656, 2.518543447, -0.4094479005, 0.4778937989, -9.825428325, 1.182090321,
      -4.56568153, 0.8396966744, 4.239966406, 0.448270897, 9.999726493, -8.966950941;
  // Its impact lies on the friction cone for μ = 0.8: μ = 1 puts it strictly inside.
  GaitOptions o = impactOptions(Landing::ImpactDoubleSupport);
  o.friction_coefficient = 1.0;
  const GaitEvaluator ev = test::defaultGaitEvaluator(o);
  const test::GradientCheck r = checkImpactGradient(ev, p);
  CHECK(r.worst_by_output.count("ds_reach_max") == 1);
}

TEST_CASE("impact landing: the step is cyclic through the impact and the leg exchange",
          "[gait][impact_gait]") {
  const GaitEvaluator ev = chevallereauEvaluator(impactOptions(Landing::ImpactSingleSupport));
  const Model& m = ev.model();
  const GaitParameters p = singleSupportImpactStep();
  const GaitEvaluation<double> e = ev.evaluate(p);
  REQUIRE(e.motion_computed);
  const std::vector<TrajectoryRow> rows = sampleTrajectory(ev, e, 1000.0);
  REQUIRE(rows.size() > 100);
  for (const TrajectoryRow& r : rows) REQUIRE(r.phase == Phase::SingleSupport);
  const TrajectoryRow& first = rows.front();
  const TrajectoryRow& last = rows.back();
  CHECK(last.t == Approx(e.T_SS).margin(1e-14));

  // Touchdown: the swing foot at (d, 0), arriving downwards.
  const PinnedTerms<double> td = pinnedTerms(m, last.q, last.qd);
  CHECK(td.foot2(0) == Approx(p(kStepLength)).margin(1e-9));
  CHECK(td.foot2(1) == Approx(0.0).margin(1e-9));
  CHECK((td.D2 * last.qd)(1) < 0.0);

  // An independent impact on the exported pre-impact state, then the leg exchange, gives the
  // exported start of the step: configuration and velocity.
  Vector7<double> X, Xd;
  floatingStateFromPinned(m, Vec5(last.q), Vec5(last.qd), X, Xd);
  const ImpactOutcome<double> o = algebraicImpact(
      m, X, Xd, ImpactBehaviour{Foot1Behaviour::Lift, Foot2Behaviour::Stick},
      ev.options().friction_coefficient);
  const Vec5 q_next = exchangeLegs(Vec5(last.q));
  const Vec5 qd_next = exchangeLegVelocities(pinnedFromFloating(o.Xd_plus));
  const double dq = (q_next - first.q).cwiseAbs().maxCoeff();
  const double dqd = (qd_next - first.qd).cwiseAbs().maxCoeff();
  std::printf("  [impact_gait] cyclicity through the impact: max |dq| %.3e, max |dqd| %.3e\n", dq,
              dqd);
  CHECK(dq < 1e-9);
  CHECK(dqd < 1e-8);
  // The lifting foot leaves the ground upwards; the stance foot before the impact is at rest.
  CHECK(o.V_plus(1) > 0.0);
  CHECK(o.slacks.minCoeff() > 0.0);
}

TEST_CASE("impact landing: the motors resupply exactly the energy the impact dissipates",
          "[gait][impact_gait]") {
  // The C&A robot has no joint friction: over a cyclic step ∫Γᵀω dt = ΔE_kinetic+potential of
  // the SS = the impact's loss. W and C_E (≥ ∫Γᵀω / d) therefore include the loss.
  const GaitEvaluator ev = chevallereauEvaluator(impactOptions(Landing::ImpactSingleSupport));
  const GaitEvaluation<double> e = ev.evaluate(singleSupportImpactStep());
  REQUIRE(e.motion_computed);
  const LandingReport r = landingReport(e.motion.landing, Landing::ImpactSingleSupport,
                                        e.alphadot_fSS);
  const double work = e.C_frott * e.step_length;
  std::printf("  [impact_gait] motor work per step %.9f J, impact loss %.9f J\n", work,
              r.energy_loss);
  CHECK(work == Approx(r.energy_loss).epsilon(1e-6));
  CHECK(e.W * e.step_length >= r.energy_loss);
  CHECK(e.C_E * e.step_length >= r.energy_loss);
}

TEST_CASE("impact landing: the consistency constraint catches a wrong behaviour",
          "[gait][impact_gait]") {
  // Foot 2's impulse of the fixture leans |I2x|/I2z ≈ 0.49 from the vertical: with μ = 0.3
  // the landing foot cannot stick, and the enumeration of the 12 behaviours agrees.
  for (const double mu : {0.8, 0.3}) {
    GaitOptions o = impactOptions(Landing::ImpactSingleSupport);
    o.friction_coefficient = mu;
    const GaitEvaluator ev = chevallereauEvaluator(o);
    const GaitEvaluation<double> e = ev.evaluate(singleSupportImpactStep());
    const ConstraintGroup& g = ev.layout()[kImpactConsistency];
    const ConstraintGroupSummary s = summarizeConstraintGroup(g, e);
    const LandingReport r = landingReport(e.motion.landing, Landing::ImpactSingleSupport, -1.0);
    const LandingSolutions all = landingSolutions(ev.model(), r, mu);
    INFO("mu " << mu << ", consistency " << s.value << ", status " << all.status);
    const double ratio = std::abs(r.impulse2(0)) / r.impulse2(1);
    if (mu > ratio) {
      CHECK(s.violated == 0);
      CHECK(e.failed_level != 1);
      CHECK(all.required_found);
    } else {
      CHECK(s.violated >= 1);
      CHECK(e.failed_level == 1);
      CHECK_FALSE(e.motion_computed);
      CHECK_FALSE(all.required_found);
      CHECK(all.count >= 1);  // the impact itself has a consistent behaviour: a slip
    }
  }
}

TEST_CASE("impact landing: gait files round-trip, bad keys are named", "[gait][impact_gait]") {
  test::ScratchDir scratch("impact_gait");
  for (const Landing landing : {Landing::ImpactSingleSupport, Landing::ImpactDoubleSupport}) {
    const GaitOptions o = impactOptions(landing);
    const std::string path = scratch.write(
        gaitYaml(test::sourcePath("configs/robot/rabbit_chevallereau_aoustin.yaml"),
                 singleSupportImpactStep(), o, ModelOptions{}));
    const GaitFile g = loadGaitFile(path);
    CHECK(g.options.parameterisation == o.parameterisation);
    CHECK(g.parameters == singleSupportImpactStep());
    CHECK(g.options.parameterisation.names().back() == "delta4s_fSS");
  }
  const std::string bad = scratch.write(
      "robot: " + test::sourcePath("configs/robot/rabbit_miossec.yaml") +
      "\nparameters: {}\noptions:\n  after_impact: double_support\n");
  test::requireConfigError([](const std::string& f) { loadGaitFile(f); }, bad,
                           "options.after_impact", 4, "needs 'landing: impact'");
}

TEST_CASE("the default landing is unchanged: no impact groups, entries or keys",
          "[gait][impact_gait]") {
  const GaitEvaluator ev = test::defaultGaitEvaluator();
  const Parameterisation& par = ev.options().parameterisation;
  CHECK(par.size() == kNumGaitParameters);
  CHECK(par.label() == "miossec");
  for (int id : {kImpactArrival, kImpactConsistency, kImpactRateRatio, kImpactOrbit})
    CHECK_FALSE(ev.layout().has(id));
  int total = 0;
  for (int id = 0; id < kImpactArrival; ++id) {
    CHECK(ev.layout().has(id));
    total += ev.layout()[id].count;
  }
  CHECK(total == ev.layout().size());
  const GaitParameters p = test::definedStep();
  const std::string json = gaitSummaryJson(ev, p, ev.evaluate(p));
  CHECK(json.find("impact") == std::string::npos);
  CHECK(json.find("landing") == std::string::npos);
  const std::string yaml = gaitYaml("robot.yaml", p, ev.options(), ModelOptions{});
  CHECK(yaml.find("landing") == std::string::npos);
  CHECK(yaml.find("parameterisation") == std::string::npos);
}

TEST_CASE("the start-rate group's unit follows its row: rad/s with DS, (rad/s)^2 without",
          "[gait][impact_gait]") {
  // Without DS the row is the cyclic α̇_iSS² condition (alphadotCyclicRow); every consumer
  // (summary.json, the CLI's worst-constraint line, the Python module) reads the layout's unit.
  const GaitEvaluator single = chevallereauEvaluator(impactOptions(Landing::ImpactSingleSupport));
  const GaitEvaluator with_ds = chevallereauEvaluator(impactOptions(Landing::ImpactDoubleSupport));
  CHECK(single.layout()[kAlphadotNegative].unit == "(rad/s)^2");
  CHECK(with_ds.layout()[kAlphadotNegative].unit == "rad/s");
  CHECK(test::defaultGaitEvaluator().layout()[kAlphadotNegative].unit == "rad/s");
  CHECK(single.layout()[kTorqueSS].unit == "N m");
  CHECK(single.layout()[kNoFallBack].unit == "(rad/s)^2");
}

TEST_CASE("touchdown_speed: V2z at touchdown plus the bound, from the sampled motion",
          "[gait][touchdown_speed]") {
  const double v_min = 0.5;
  const GaitEvaluator ev = chevallereauEvaluator(touchdownOptions(v_min));
  const GaitEvaluation<double> e = ev.evaluate(singleSupportImpactStep());
  REQUIRE(e.motion_computed);
  const ConstraintGroup& g = ev.layout()[kTouchdownSpeed];
  REQUIRE(g.count == 1);
  CHECK(g.unit == "m/s");
  CHECK(g.level == 5);
  CHECK(constraintGroupScale(kTouchdownSpeed, ev.model()) == 1.0);
  CHECK(e.state[g.offset] == ConstraintState::Defined);
  const double vz = swingFootVz(ev, e);
  CHECK(vz < 0.0);  // the foot arrives moving down (2.2)
  CHECK(e.g[g.offset] == Approx(vz + v_min).margin(1e-9));
}

TEST_CASE("touchdown_speed: exact gradient equals finite differences",
          "[gait][touchdown_speed][derivatives]") {
  const GaitEvaluator ev = chevallereauEvaluator(touchdownOptions(0.5));
  const GaitParameters p = singleSupportImpactStep();
  const GaitGradient grad = ev.evaluateWithGradient(p);
  const int k = ev.layout()[kTouchdownSpeed].offset;
  const test::GradientCheck r = test::checkGradient(
      ev, p,
      {{"touchdown_speed", [k](const GaitEvaluation<double>& e) { return e.g[k]; },
        grad.dg.row(k).transpose()}},
      [](const std::string& name) { return name; });
  INFO(r.failures);
  CHECK(r.failed == 0);
  CHECK(r.skipped == 0);
  int used = 0;
  for (int i = 0; i < p.size(); ++i) used += ev.options().parameterisation.isUsed(i) ? 1 : 0;
  CHECK(r.checked == used);
  CHECK(grad.dg.row(k).norm() > 0.0);
}

TEST_CASE("touchdown_speed: present only with an impact and a bound, refused otherwise",
          "[gait][touchdown_speed]") {
  CHECK_FALSE(chevallereauEvaluator(touchdownOptions(0.0)).layout().has(kTouchdownSpeed));
  CHECK_FALSE(test::defaultGaitEvaluator().layout().has(kTouchdownSpeed));
  GaitOptions zero_velocity;
  zero_velocity.touchdown_speed_min = 0.5;
  CHECK_THROWS_WITH(test::defaultGaitEvaluator(zero_velocity),
                    Catch::Matchers::Contains("touchdown_speed_min needs a landing with impact"));

  test::ScratchDir scratch("touchdown_speed");
  const std::string path =
      scratch.write(gaitYaml(test::sourcePath("configs/robot/rabbit_chevallereau_aoustin.yaml"),
                             singleSupportImpactStep(), touchdownOptions(0.5), ModelOptions{}));
  CHECK(loadGaitFile(path).options.touchdown_speed_min == 0.5);
  const std::string bad = scratch.write(
      "robot: " + test::sourcePath("configs/robot/rabbit_miossec.yaml") +
      "\nparameters: {}\noptions:\n  touchdown_speed_min: 0.5\n");
  test::requireConfigError([](const std::string& f) { loadGaitFile(f); }, bad,
                           "options.touchdown_speed_min", 4, "needs 'landing: impact'");
}

TEST_CASE("the shipped touchdown-speed gait meets the ground at least at its bound",
          "[gait][touchdown_speed]") {
  const test::ShippedGait f("configs/gait/default_impact.yaml");
  const double v_min = f.gait.options.touchdown_speed_min;
  // A vertical tracking error of 1 mm moves touchdown by at most 2 ms.
  REQUIRE(v_min >= 1e-3 / 2e-3);
  REQUIRE(f.evaluation.motion_computed);
  CHECK(feasibilityVerdict(f.evaluator, f.gait.parameters, f.evaluation).feasible);
  CHECK(swingFootVz(f.evaluator, f.evaluation) <= -v_min + 1e-6);
}
