// The optimiser's final verdict with dry friction turned off explicitly: the viscous-only
// problem converges, but its optimum needs more than the torque envelope once the robot's
// Coulomb friction (which the exported feedforward adds) is counted, so the run is not optimal
// and says which group exceeds the envelope by how much.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "gaitopt/gait/constraint_summary.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/opt/initial_guess.hpp"
#include "gaitopt/opt/optimizer.hpp"
#include "test_support.hpp"

using namespace gaitopt;

TEST_CASE("optimize with dry_friction false: not optimal, the torque group and excess named",
          "[optimize][robot_friction]") {
  OptimizeConfig c = loadOptimizeConfig(test::sourcePath("configs/default.yaml"));
  REQUIRE(c.options.dry_friction);  // the default
  c.options.dry_friction = false;
  const GaitEvaluator ev(c.robot, c.options, c.model_options);
  OptimizationRequest request = optimizationRequest(c, configuredInitialGuess(c, ev.model()));
  request.solver.print_every = 0;
  const OptimizationResult r = optimizeGait(ev, request);
  INFO("status " << r.status << ", C_Gamma " << r.evaluation.C_Gamma);
  REQUIRE(r.evaluation.motion_computed);
  // Every constraint of the viscous-only problem holds at the nodes ...
  for (int id = 0; id < kNumConstraintGroups; ++id)
    if (ev.layout().has(id))
      CHECK(summarizeConstraintGroup(ev.layout()[id], r.evaluation).value <=
            kFeasibilityTolerance * constraintGroupScale(id, ev.model()));
  // ... but not the envelope with the robot's friction.
  CHECK(r.status == OptimizationStatus::Infeasible);
  CHECK_FALSE(isOptimal(r));
  CHECK(r.unmet_level == 5);
  CHECK(std::find(r.unmet_constraints.begin(), r.unmet_constraints.end(), "torque_envelope_ss") !=
        r.unmet_constraints.end());
  REQUIRE(r.robot_friction.checked);
  CHECK_FALSE(r.robot_friction.met);
  CHECK(r.robot_friction.worst_group == kTorqueSS);
  // Of the order of the hips' 16.5 N·m of Coulomb friction, at most all of it.
  CHECK(r.robot_friction.excess > 1.0);
  CHECK(r.robot_friction.excess <= *std::max_element(c.robot.coulomb.begin(), c.robot.coulomb.end()));
  CHECK(r.constraint_violation >= r.robot_friction.excess);
  CHECK_THAT(robotFrictionMessage(ev.layout(), r.robot_friction),
             Catch::Matchers::StartsWith("torque_envelope_ss exceeds the torque envelope by "));
}
