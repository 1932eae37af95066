// The elastic problem of opt/infeasibility_certificate.hpp: a speed made infeasible for an
// independent reason (a joint-limit margin wider than half a knee's range: no knee angle
// meets both of its rows) is certified with the knee rows blocking and s* at least the margin's
// excess; a feasible optimum gives no certificate; at every first-order point with s* > 0 the
// blocking rows are at s*; row names.
#include <catch2/catch.hpp>
#include <cmath>

#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/opt/gait_problem.hpp"
#include "gaitopt/opt/infeasibility_certificate.hpp"
#include "gaitopt/opt/initial_guess.hpp"
#include "test_gait_support.hpp"

namespace gaitopt::test {

TEST_CASE("Elastic problem: a joint-limit margin no knee angle can meet is certified",
          "[certificate]") {
  GaitOptions options = viscousOptions();
  const RobotParams robot = robotFile("rabbit_miossec");
  const double knee_range = robot.limits.knee_max - robot.limits.knee_min;
  // Upper row δ − max + m and lower row min + m − δ sum to 2m − range: one of them is at least
  // (2m − range)/2 whatever δ, at every node (scale 1: radians).
  options.joint_limit_margin = 0.5 * knee_range + 0.05;
  const double bound = 0.05;
  const GaitEvaluator ev(robot, options);
  // From the step optimal without the margin, far off (0.8 rad): more iterations than a
  // sweep's attempts need.
  const InfeasibilityCertificate c = minimiseViolation(ev, optimalStep(), 0.5, 1000);
  INFO("s* " << c.min_violation << ", " << c.blocking.size() << " blocking rows");
  REQUIRE(c.infeasible());
  CHECK(c.min_violation >= bound - 1e-6);
  CHECK_FALSE(c.feasible);
  // The multipliers sum to 1 (∂/∂s of the Lagrangian); those listed are ≥ 1e-3.
  double sum = 0.0;
  for (const BlockingConstraint& b : c.blocking) {
    CHECK(b.multiplier >= kBlockingMultiplier);
    sum += b.multiplier;
  }
  CHECK(sum <= 1.0 + 1e-6);
  CHECK(sum >= 0.9);
  // The largest share: a knee row of the joint limits, at s* (active; its unit radians).
  const BlockingConstraint& top = c.blocking.front();
  INFO(top.name);
  CHECK(top.name.rfind("joint_limits_", 0) == 0);
  CHECK(top.name.find("knee") != std::string::npos);
  CHECK(top.unit == "rad");
  CHECK(top.value == Approx(c.min_violation).margin(1e-4));
  for (std::size_t i = 1; i < c.blocking.size(); ++i)
    CHECK(c.blocking[i - 1].multiplier >= c.blocking[i].multiplier);
}

TEST_CASE("Elastic problem: an optimum's rows can be met, no certificate", "[certificate]") {
  // The step optimal at 0.5 m/s meets every row (the verdict of these options adds the
  // robot's Coulomb friction to the torque envelope, which is not a row).
  const GaitEvaluator ev = defaultGaitEvaluator();
  const InfeasibilityCertificate c = minimiseViolation(ev, optimalStep(), 0.5);
  CHECK(c.min_violation <= kFeasibilityTolerance);
  CHECK_FALSE(c.infeasible());
  CHECK(c.blocking.empty());
  CHECK(std::abs(ev.evaluate(c.x).speed - 0.5) <= kFeasibilityTolerance);
}

TEST_CASE("Elastic problem: a first-order point with s* > 0 has its blocking rows at s*",
          "[certificate]") {
  // Starts from which SLSQP ended the elastic problem with s = 0 below rows it left unmet
  // (+0.47 scaled), or with a row met exactly (g = 0, a friction cone held by the DS force
  // split's clamp, zero gradient) taken as blocking; and the knee margin no angle meets.
  const GaitFile g = loadGaitFile(sourcePath("configs/gait/default_step.yaml"));
  const GaitEvaluator step(g.robot, g.options, g.model_options);
  GaitOptions margin = viscousOptions();
  const RobotParams robot = robotFile("rabbit_miossec");
  margin.joint_limit_margin = 0.5 * (robot.limits.knee_max - robot.limits.knee_min) + 0.05;
  const GaitEvaluator knees(robot, margin);
  const struct {
    const GaitEvaluator& ev;
    GaitParameters start;
    double speed;
  } cases[] = {{step, defaultInitialGuess(step.model(), 0.10), 0.10},
               {step, g.parameters, 0.15},
               {step, g.parameters, 0.10},
               {knees, optimalStep(), 0.5}};
  int certified = 0;
  for (const auto& c : cases) {
    const InfeasibilityCertificate cert = minimiseViolation(c.ev, c.start, c.speed, 1000);
    INFO("v " << c.speed << ": s* " << cert.min_violation << ", converged " << cert.converged
              << ", " << cert.blocking.size() << " blocking rows");
    if (!cert.converged || cert.min_violation <= kFeasibilityTolerance) continue;
    // s > 0 at a first-order point: ∂/∂s of the Lagrangian puts Σ λ = 1 on rows at s*.
    REQUIRE(cert.infeasible());
    ++certified;
    double sum = 0.0;
    for (const BlockingConstraint& b : cert.blocking) {
      const double scaled = b.value / constraintScale(c.ev.layout(), c.ev.model(), b.entry);
      INFO(b.name << ": " << b.value << " " << b.unit << ", multiplier " << b.multiplier);
      CHECK(scaled >= 0.5 * cert.min_violation);
      CHECK(scaled <= cert.min_violation + 1e-12);
      sum += b.multiplier;
    }
    CHECK(sum >= 0.9);
    CHECK(sum <= 1.0 + 1e-6);
  }
  CHECK(certified >= 1);  // the knee margin
}

TEST_CASE("constraintRowName: group, joint or foot, side, node", "[certificate]") {
  const GaitEvaluator ev = defaultGaitEvaluator();
  const ConstraintLayout& l = ev.layout();
  // torque_envelope_ss: 8 rows per node, joint j's (upper, lower) at 2j.
  CHECK(constraintRowName(l, l[kTorqueSS].offset + 8 * 3 + 2 * 3 + 1) ==
        "torque_envelope_ss knee 2 lower at SS node 3");
  CHECK(constraintRowName(l, l[kJointLimitsDS].offset + 8 * 2 + 2) ==
        "joint_limits_ds hip 1 upper at DS node 2");
  // friction_cone_ds: per node foot 1 (+R_x, −R_x), then foot 2.
  CHECK(constraintRowName(l, l[kFrictionConeDS].offset + 4 * 5 + 3) ==
        "friction_cone_ds foot 2 -R_x at DS node 5");
  // The clearance skips the phase's first node.
  CHECK(constraintRowName(l, l[kClearance].offset) == "clearance at SS node 1");
  CHECK(constraintRowName(l, l[kReachMaxIDS].offset) == "reach_max_iDS");
  CHECK(constraintGroupOf(l, l[kNormalForceSS].offset + 4) == kNormalForceSS);
  CHECK(constraintGroupOf(l, l.size()) == -1);
}

}  // namespace gaitopt::test
