#pragma once
// The shipped default gait (configs/gait/default_step.yaml) evaluated, with the model of its
// robot file carrying the whole friction (what exports and closed-loop simulations use).
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

struct DefaultGait {
  GaitFile gait = loadGaitFile(sourcePath("configs/gait/default_step.yaml"));
  GaitEvaluator evaluator{gait.robot, gait.options, gait.model_options};
  GaitEvaluation<double> evaluation = evaluator.evaluate(gait.parameters);
  Model model = buildModel(gait.robot, gait.model_options);
};

}  // namespace gaitopt::test
