// The elastic problem of opt/infeasibility_certificate.hpp: a speed made infeasible for an
// independent reason (a joint-limit margin wider than half a knee's range: no knee angle
// meets both of its rows) is certified with the knee rows blocking and s* at least the margin's
// excess; a feasible optimum gives no certificate; at every first-order point with s* > 0 the
// blocking rows are at s*; a step whose rows hold but not the verdict between the nodes gets the
// rows of the verdict's own finer grid (nested in the optimiser's); row names.
#include <catch2/catch.hpp>
#include <cmath>

#include "gaitopt/gait/feasibility.hpp"
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

// The step the 10-speed library keeps at 0.95 m/s on configs/default.yaml: its rows hold, the
// 10× finer check does not (a sign change of the Coulomb torque between two SS nodes).
GaitFile unmetBetweenNodes() {
  return loadGaitFile(sourcePath("tests/data/gait_optima/default_0.95_unmet_between.yaml"));
}

TEST_CASE("Elastic problem: rows met, the verdict broken between the nodes: a point meeting it",
          "[certificate]") {
  const GaitFile g = unmetBetweenNodes();
  const GaitEvaluator ev(g.robot, g.options, g.model_options);
  const double v = 0.95;
  // The start: every level-5 row within the tolerance at the nodes, the SS torque envelope
  // 1e-2 scaled (1.4 N m) and more over between them.
  const GaitEvaluation<double> e = ev.evaluate(g.parameters);
  for (int k = 0; k < ev.layout().size(); ++k)
    if (ev.layout().levelOf(k) == 5 && e.state[k] != ConstraintState::NotComputed)
      REQUIRE(e.g[k] / constraintScale(ev.layout(), ev.model(), k) <= kFeasibilityTolerance);
  const FeasibilityVerdict start = feasibilityVerdict(ev, g.parameters, e, v);
  REQUIRE_FALSE(start.feasible);
  CHECK(start.between_nodes.worst_group == kTorqueSS);
  CHECK(start.between_nodes.worst_scaled > 1e-2);

  // The elastic problem ends on a point meeting the one verdict (nodes, the finer grid, the
  // speed): no certificate, and a start the optimiser can be restarted from.
  const InfeasibilityCertificate c = minimiseViolation(ev, g.parameters, v);
  INFO("s* " << c.min_violation << ", converged " << c.converged);
  const FeasibilityVerdict end = feasibilityVerdict(ev, c.x, ev.evaluate(c.x), v);
  CHECK(end.feasible);
  CHECK(end.between_nodes.worst_scaled <= kFeasibilityTolerance);
  CHECK(c.feasible);
  CHECK(c.min_violation <= kFeasibilityTolerance);
  CHECK_FALSE(c.infeasible());
  CHECK(c.blocking.empty());
}

TEST_CASE("The verdict's finer grid holds the optimiser's nodes: node 10 k is node k",
          "[certificate]") {
  // Chebyshev–Lobatto nodes cos(π k / N) and cos(π 10 k / 10 N) coincide: the same step gives
  // the same row values there, so a row of the finer grid lies in one interval of the
  // optimiser's grid (the certificate names it so).
  const GaitFile g = unmetBetweenNodes();
  const GaitEvaluator ev(g.robot, g.options, g.model_options);
  const GaitEvaluator fine = betweenNodesEvaluator(ev);
  CHECK(fine.options().ss_nodes == kBetweenNodesRefinement * ev.options().ss_nodes);
  CHECK(fine.options().ds_nodes == kBetweenNodesRefinement * ev.options().ds_nodes);
  const GaitEvaluation<double> coarse = ev.evaluate(g.parameters), refined = fine.evaluate(g.parameters);
  int compared = 0;
  for (int id : {kTorqueSS, kJointLimitsSS, kClearance, kTorqueDS, kFrictionConeDS,
                 kNormalForceDS}) {
    const ConstraintGroup& c = ev.layout()[id];
    const ConstraintGroup& f = fine.layout()[id];
    REQUIRE(c.per_point == f.per_point);
    REQUIRE(c.first_point == f.first_point);
    for (int k = c.offset; k < c.offset + c.count; ++k) {
      const int node = (k - c.offset) / c.per_point + c.first_point;
      const int sub = (k - c.offset) % c.per_point;
      const int j = f.offset + (kBetweenNodesRefinement * node - f.first_point) * f.per_point + sub;
      INFO(constraintRowName(ev.layout(), k));
      CHECK(refined.g[j] == Approx(coarse.g[k]).margin(1e-9 * constraintGroupScale(id, ev.model())));
      ++compared;
    }
  }
  CHECK(compared > 500);
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
