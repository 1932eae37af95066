// The torque envelope with the robot's whole friction: a step evaluated without dry friction is
// not feasible when the feedforward the export computes (with the robot's Coulomb friction)
// leaves the envelope, the verdict names the group and the excess; the shipped default optimum,
// planned with dry friction, keeps its exported feedforward within the envelope.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/gait/constraint_summary.hpp"
#include "gaitopt/gait/feasibility.hpp"
#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/io/summary_file.hpp"
#include "gaitopt/model/joint_friction.hpp"
#include "gaitopt/model/torque_envelope.hpp"
#include "test_default_gait.hpp"
#include "test_gait_support.hpp"

using namespace gaitopt;

namespace {

// Largest |Γ*_j + Coulomb_j| − Γmax(ω_j) over the SS of a step evaluated without dry friction,
// sampled at 10 kHz: Γ* of the evaluator (viscous friction only) plus the robot's Coulomb
// friction with the smooth sign, as the export adds it.
double sampledSsExcess(const GaitEvaluator& ev, const GaitEvaluation<double>& e) {
  const Model full = buildModel(ev.model().robot, ev.model().options);
  double worst = -std::numeric_limits<double>::infinity();
  const int n = static_cast<int>(std::ceil(e.T_SS * 1e4));
  for (int i = 0; i <= n; ++i) {
    const TrajectoryRow r =
        sampleTrajectoryAt(ev, e, Phase::SingleSupport, e.T_SS * i / static_cast<double>(n));
    const Vec4 w = jointSpeeds(r.qd);
    for (int j = 0; j < 4; ++j) {
      const double coulomb =
          full.coulomb(j) * std::tanh(w(j) / full.options.friction_smoothing);
      worst = std::max(worst, std::abs(r.gamma_star(j) + coulomb) -
                                  torqueLimit(full.robot.envelope, w(j), true));
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("without dry friction the verdict checks the envelope with the robot's friction",
          "[gait][robot_friction]") {
  GaitOptions o;
  o.dry_friction = false;
  o.target_speed = 0.5;
  const GaitEvaluator ev = test::defaultGaitEvaluator(o);
  // The C_Gamma optimum of the viscous-only problem: every constraint of that problem holds.
  const GaitParameters p = test::optimalStep();
  const GaitEvaluation<double> e = ev.evaluate(p);
  REQUIRE(e.motion_computed);
  REQUIRE(summarizeConstraintGroup(ev.layout()[kTorqueSS], e).value <= 1e-3);

  const FeasibilityVerdict v = feasibilityVerdict(ev, p, e);
  const RobotFrictionCheck& c = v.robot_friction;
  REQUIRE(c.checked);
  CHECK_FALSE(c.met);
  CHECK_FALSE(v.feasible);
  CHECK(v.failed_level == 5);
  CHECK(c.worst_group == kTorqueSS);
  CHECK(std::find(v.unmet_groups.begin(), v.unmet_groups.end(), "torque_envelope_ss") !=
        v.unmet_groups.end());
  // The Coulomb friction at the hips is 16.5 N·m: the excess is of that order, and the one a
  // fine sampling of the feedforward finds (the check also looks between its 10× finer nodes).
  const double sampled = sampledSsExcess(ev, e);
  CHECK(sampled > 1.0);
  CHECK(c.excess >= sampled - 1e-3);
  CHECK(c.excess == Approx(sampled).margin(0.05));
  CHECK(v.max_violation >= c.excess);

  const std::string message = robotFrictionMessage(ev.layout(), c);
  CHECK_THAT(message, Catch::Matchers::StartsWith("torque_envelope_ss exceeds the torque "
                                                  "envelope by "));
  char excess[32];
  std::snprintf(excess, sizeof excess, "%.4g N m", c.excess);
  CHECK_THAT(message, Catch::Matchers::Contains(excess));
  CHECK_THAT(message, Catch::Matchers::Contains("dry_friction: false"));

  const std::string json = gaitSummaryJson(ev, p, e);
  CHECK_THAT(json, Catch::Matchers::Contains("\"robot_friction\""));
  CHECK_THAT(json, Catch::Matchers::Contains(message));
  CHECK_THAT(json, Catch::Matchers::Contains("\"feasible\": false"));
}

TEST_CASE("the robot-friction check is made only without dry friction on a robot that has it",
          "[gait][robot_friction]") {
  const GaitParameters p = test::optimalStep();
  const GaitEvaluator with_dry = test::defaultGaitEvaluator(GaitOptions{});
  CHECK(with_dry.options().dry_friction);  // the default
  CHECK_FALSE(feasibilityVerdict(with_dry, p, with_dry.evaluate(p)).robot_friction.checked);
  CHECK(gaitSummaryJson(with_dry, p, with_dry.evaluate(p)).find("robot_friction") ==
        std::string::npos);
  GaitOptions o;
  o.dry_friction = false;
  const GaitEvaluator frictionless(test::robotFile("rabbit_chesse"), o);
  CHECK_FALSE(feasibilityVerdict(frictionless, p, frictionless.evaluate(p)).robot_friction.checked);
}

TEST_CASE("the default optimum's exported feedforward stays within the torque envelope",
          "[gait][robot_friction]") {
  const test::DefaultGait f;
  REQUIRE(f.gait.options.dry_friction);
  REQUIRE(feasibilityVerdict(f.evaluator, f.gait.parameters, f.evaluation).feasible);
  ExportRequest req;  // the export's defaults: 1 step at 1 kHz
  req.steps = 2;
  const std::vector<ExportRow> rows = exportTrajectory(f.evaluator, f.evaluation, f.model, req);
  REQUIRE(rows.size() > 1000);
  double worst = -std::numeric_limits<double>::infinity();
  for (const ExportRow& r : rows)
    for (int j = 0; j < 4; ++j)
      worst = std::max(worst, std::abs(r.tau(j)) - torqueLimit(f.model.robot.envelope, r.phid(j),
                                                               f.gait.options.full_torque_envelope));
  INFO("largest |tau| - limit over the exported samples: " << worst << " N m");
  CHECK(worst <= 1e-6);
}
