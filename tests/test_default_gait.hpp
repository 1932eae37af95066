#pragma once
// The shipped default gait (configs/gait/default_step.yaml), or another shipped gait, evaluated, with the model of its
// robot file carrying the whole friction (what exports and closed-loop simulations use).
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

// A shipped gait file (path relative to the source tree) evaluated, with its robot's model.
struct ShippedGait {
  explicit ShippedGait(const std::string& relative_path)
      : gait(loadGaitFile(sourcePath(relative_path))) {}
  GaitFile gait;
  GaitEvaluator evaluator{gait.robot, gait.options, gait.model_options};
  GaitEvaluation<double> evaluation = evaluator.evaluate(gait.parameters);
  Model model = buildModel(gait.robot, gait.model_options);
};

struct DefaultGait : ShippedGait {
  DefaultGait() : ShippedGait("configs/gait/default_step.yaml") {}
};

}  // namespace gaitopt::test
