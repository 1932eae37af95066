// The closed loop with the impact model, the constrained control law and the plant's contact
// checks: impact touchdowns equal the impact solver's post-impact state, the impact-landing
// gait converges to its cycle, the torque projection keeps Γ* within the envelope, a low-μ
// ground makes the stance foot slip, and the energy balance holds over whole steps.
#include <catch2/catch.hpp>

#include "gaitopt/gait/impact_landing.hpp"
#include "gaitopt/gait/leg_geometry.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/forward_dynamics.hpp"
#include "gaitopt/model/joint_friction.hpp"
#include "gaitopt/model/torque_envelope.hpp"
#include "gaitopt/sim/hybrid_walk.hpp"
#include "gaitopt/sim/impact_touchdown.hpp"
#include "test_default_gait.hpp"
#include "test_support.hpp"
#include "test_walk_request.hpp"

namespace gaitopt::test {
namespace {

struct ImpactGait : ShippedGait {
  ImpactGait() : ShippedGait("configs/gait/chevallereau_aoustin_0.75_impact.yaml") {}
};

// Largest |Γ*_j| / limit_j(ω_j) over the samples.
double torqueRatio(const Model& m, const WalkResult& r, bool full) {
  double worst = 0.0;
  for (const WalkSample& s : r.samples) {
    const Vec4 w = jointSpeeds(s.qd);
    for (int j = 0; j < 4; ++j)
      worst =
          std::max(worst, std::abs(s.gamma_star(j)) / torqueLimit(m.robot.envelope, w(j), full));
  }
  return worst;
}

}  // namespace

TEST_CASE("Impact touchdown equals the impact solver's post-impact state", "[sim][impact]") {
  const ImpactGait f;
  REQUIRE(f.evaluation.defined());
  const GaitMotion<double>& mo = f.evaluation.motion;
  const double mu = f.gait.options.friction_coefficient;
  // The gait's touchdown state: q_fSS with q̇ = q*(α_fSS) α̇_fSS.
  const Vec5 qd = mo.landing.slopes_before * mo.alphadot_fSS;
  ImpactOptions io;
  io.mu = mu;
  const ImpactResult direct =
      solveImpactFromPinned(f.model, mo.q_fSS, qd, ImpactModelKind::Algebraic, io);
  REQUIRE(direct.status == ImpactStatus::Unique);
  const TouchdownResult td = gaitTouchdown(f.gait.options, "auto", mu)(f.model, mo.q_fSS, qd);
  REQUIRE(td.ok);
  CHECK_FALSE(td.double_support_follows);
  CHECK(td.behaviour == "lift/stick");
  const Vec5 expected = exchangeLegVelocities(Vec5(direct.solutions[0].Xd_plus.head<5>()));
  CHECK((td.qd_plus - expected).lpNorm<Eigen::Infinity>() <= 1e-12);
  CHECK((td.q_plus - exchangeLegs(mo.q_fSS)).lpNorm<Eigen::Infinity>() == 0.0);
  CHECK(td.energy_loss == Approx(direct.solutions[0].energy_loss).epsilon(1e-12));
  // and the gait's own landing: α̇⁺ = λ α̇⁻, post-impact slopes.
  const LandingReport rep =
      landingReport(mo.landing, f.gait.options.parameterisation.landing, mo.alphadot_fSS);
  CHECK(td.qd_plus(0) == Approx(rep.alphadot_plus).epsilon(1e-10));
  CHECK(td.energy_loss == Approx(rep.energy_loss).epsilon(1e-10));
  // The pinned energy after the impact (new stance foot at rest) is the energy before minus
  // the loss.
  CHECK(pinnedEnergy(f.model, td.q_plus, td.qd_plus) ==
        Approx(pinnedEnergy(f.model, mo.q_fSS, qd) - td.energy_loss).epsilon(1e-10));
  SECTION("differential model: the same impact (one phase)") {
    const TouchdownResult d =
        gaitTouchdown(f.gait.options, "differential", mu)(f.model, mo.q_fSS, qd);
    REQUIRE(d.ok);
    CHECK((d.qd_plus - td.qd_plus).lpNorm<Eigen::Infinity>() <= 1e-9);
  }
  SECTION("a gait needing a DS: the rear foot lifting ends the walk") {
    ImpactOptions o;
    o.mu = mu;
    const TouchdownResult r =
        impactTouchdown(ImpactModelKind::Algebraic, o, true)(f.model, mo.q_fSS, qd);
    CHECK_FALSE(r.ok);
    CHECK(r.failure == WalkOutcome::RearFootLift);
  }
  SECTION("low friction: the landing foot slides") {
    ImpactOptions o;
    o.mu = 0.05;
    const TouchdownResult r =
        impactTouchdown(ImpactModelKind::Algebraic, o, false)(f.model, mo.q_fSS, qd);
    CHECK_FALSE(r.ok);
    CHECK(r.failure == WalkOutcome::Slipped);
    CHECK_THAT(r.why, Catch::Matchers::Contains("slides"));
  }
}

TEST_CASE("Impact-landing gait: the closed loop converges to its cycle with its energy balance",
          "[sim][impact]") {
  const ImpactGait f;
  const GaitMotion<double>& mo = f.evaluation.motion;
  const int steps = lightTests() ? 4 : 10;
  WalkRequest req = gaitRequest(f.gait.options, steps);
  req.dalphad0 = 0.05;
  const WalkResult r =
      simulateWalk(f.evaluation, f.model, f.model, req,
                   gaitTouchdown(f.gait.options, "auto", req.friction_coefficient));
  INFO(r.message);
  REQUIRE(r.outcome == WalkOutcome::Completed);
  REQUIRE(static_cast<int>(r.steps.size()) == steps);
  const double first = std::abs(r.steps[0].alphad_start - mo.alphadot_iSS);
  CHECK(first == Approx(0.05).margin(1e-12));
  for (const WalkStep& s : r.steps) {
    CHECK(s.impact_behaviour == "lift/stick");
    CHECK_FALSE(s.double_support);
    CHECK(s.impact_energy_loss > 0.0);
    CHECK(s.touchdown_event_residual <= 1e-9);
    CHECK(std::abs(stepEnergyBalanceError(s)) <= 1e-8);
    CHECK(s.saturated_samples == 0);
  }
  // The zero dynamics through the impact contract (r² < 1): |Δα̇| decays step after step.
  const double last = std::abs(r.steps.back().alphad_start - mo.alphadot_iSS);
  CHECK(last < (lightTests() ? 0.5 : 0.05) * first);
  CHECK(r.steps.back().max_output_error < 1e-3);
}

TEST_CASE("Energy balance over whole steps with double support", "[sim]") {
  const DefaultGait f;
  WalkRequest req = gaitRequest(f.gait.options, 2);
  req.dalphad0 = 0.01;
  const WalkResult r =
      simulateWalk(f.evaluation, f.model, f.model, req,
                   gaitTouchdown(f.gait.options, "auto", req.friction_coefficient));
  INFO(r.message);
  REQUIRE(r.outcome == WalkOutcome::Completed);
  for (const WalkStep& s : r.steps) {
    CHECK(s.double_support);
    CHECK(s.impact_energy_loss < 1e-9);  // the foot grazes the ground: a round-off impact
    CHECK(std::abs(s.step_motor_work - s.motor_work) > 1e-3);  // the DS does work too
    CHECK(std::abs(stepEnergyBalanceError(s)) <= 1e-8);
  }
}

TEST_CASE("Torque projection keeps the motor torques within the envelope", "[sim]") {
  const DefaultGait f;
  WalkRequest req = gaitRequest(f.gait.options, 1);
  req.dq0(3) = 0.15;  // swing hip: the PD asks for more than the motors give
  req.bandwidth = 60.0;
  req.torque_limits = false;
  const WalkResult free = simulateWalk(f.evaluation, f.model, f.model, req);
  REQUIRE(torqueRatio(f.model, free, req.full_torque_envelope) > 1.2);
  req.torque_limits = true;
  const WalkResult limited = simulateWalk(f.evaluation, f.model, f.model, req);
  INFO(limited.message);
  REQUIRE(!limited.steps.empty());
  CHECK(limited.steps[0].saturated_samples > 0);
  CHECK(limited.steps[0].first_saturation_time == Approx(0.0).margin(1e-12));
  CHECK(torqueRatio(f.model, limited, req.full_torque_envelope) <= 1.0 + 1e-9);
}

TEST_CASE("Contact projection: a faster start walks with its DS normal force held at R_min",
          "[sim]") {
  const DefaultGait f;
  WalkRequest req = gaitRequest(f.gait.options, 2);
  REQUIRE(req.min_normal_force == 20.0);  // the gait's min_normal_force
  const TouchdownMap td = gaitTouchdown(f.gait.options, "auto", req.friction_coefficient);
  // 2 % faster: the free DS pulls the rear foot off the ground (the gait's DS normal force
  // sits at its 20 N bound).
  req.dalphad0 = -0.02;
  req.torque_limits = false;
  const WalkResult free = simulateWalk(f.evaluation, f.model, f.model, req, td);
  CHECK(free.outcome == WalkOutcome::StanceLiftOff);
  req.torque_limits = true;
  for (const double r_min : {20.0, 0.0}) {
    DYNAMIC_SECTION("R_min = " << r_min << " N") {
      req.min_normal_force = r_min;
      const WalkResult held = simulateWalk(f.evaluation, f.model, f.model, req, td);
      INFO(held.message);
      REQUIRE(held.outcome == WalkOutcome::Completed);
      double least = 1e9;
      for (const WalkSample& s : held.samples)
        if (!s.single_support) least = std::min({least, s.R1(1), s.R2(1)});
      CHECK(least >= r_min - 1e-6);
      CHECK(least <= r_min + 1e-3);  // the bound was active
      // Held at 20 N the DS gives way on α: after one step the cycle's α̇ is restored to
      // 0.5 % of the perturbation, at 0 N to 0.15 %.
      const double share = r_min > 0.0 ? 0.005 : 0.0015;
      CHECK(held.steps[1].alphad_start ==
            Approx(f.evaluation.motion.alphadot_iSS).margin(share * std::abs(req.dalphad0)));
    }
  }
}

TEST_CASE("Low-friction ground: the stance foot slips", "[sim]") {
  const DefaultGait f;
  WalkRequest req = gaitRequest(f.gait.options, 2);
  req.plant_friction_coefficient = 0.15;
  const WalkResult r = simulateWalk(f.evaluation, f.model, f.model, req);
  CHECK(r.outcome == WalkOutcome::Slipped);
  CHECK_THAT(r.message, Catch::Matchers::Contains("friction cone"));
  CHECK_THAT(r.message, Catch::Matchers::Contains("step 0"));
  REQUIRE(!r.samples.empty());
  CHECK_THAT(r.message, Catch::Matchers::Contains("at t = "));
  // The event is located on the cone boundary |Rx| = μ Rz (widened by the round-off margin of
  // 10⁻⁷ of the weight).
  const WalkSample& s = r.samples.back();
  REQUIRE(s.single_support);
  const double margin = 1e-7 * f.model.total_mass * f.model.gravity;
  CHECK(std::abs(s.R1(0)) - 0.15 * s.R1(1) == Approx(margin).margin(1e-9));
}

TEST_CASE("Time-optimal DS control of alpha reaches the cyclic curve", "[sim]") {
  const DefaultGait f;
  const GaitMotion<double>& mo = f.evaluation.motion;
  WalkRequest req = gaitRequest(f.gait.options, 3);
  req.ds_control = DsAlphaControl::TimeOptimal;
  req.dalphad0 = 0.01;
  const WalkResult r =
      simulateWalk(f.evaluation, f.model, f.model, req,
                   gaitTouchdown(f.gait.options, "auto", req.friction_coefficient));
  INFO(r.message);
  REQUIRE(r.outcome == WalkOutcome::Completed);
  for (std::size_t k = 1; k < r.steps.size(); ++k)
    CHECK(r.steps[k].alphad_start == Approx(mo.alphadot_iSS).margin(1e-6));
  CHECK(r.steps[2].t_liftoff - r.steps[2].t_touchdown == Approx(mo.T_DS).margin(1e-6));
}

}  // namespace gaitopt::test
