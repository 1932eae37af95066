#pragma once
// A shipped optimiser configuration under the conditions the optimiser tests' measured
// behaviours (local optima, restarts, iteration counts) were found in: viscous joint friction
// only (the robot's Coulomb friction set to 0, so that the verdict has none to add) and the
// whole friction cone, from the default start. The shipped configurations plan with dry friction and
// friction_coefficient 0.6 (docs/commands/optimize.md, "Joint friction and the friction margin of the shipped
// configurations"), which moves SLSQP's default start to other local optima.
#include <string>

#include "gaitopt/io/optimize_config.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

inline OptimizeConfig viscousConfig(const std::string& name) {
  OptimizeConfig c = loadOptimizeConfig(sourcePath("configs/" + name));
  c.robot.coulomb.fill(0.0);
  c.options.friction_coefficient = 0.8;
  c.initial_guess_path.reset();  // the default start (configs/chesse_0.85.yaml has another)
  return c;
}

}  // namespace gaitopt::test
