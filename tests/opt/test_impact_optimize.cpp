// The optimiser on a gait landing with an impact (docs/science/impact-gaits.md): the shipped
// C&A configuration loads with its landing, the parameters this family does not read stay
// fixed, and a perturbed start returns to the shipped optimum with a unique impact.
#include <catch2/catch.hpp>

#include <cstdio>

#include "gaitopt/gait/impact_landing.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/opt/gait_problem.hpp"
#include "gaitopt/opt/optimizer.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

using namespace gaitopt;
using gaitopt::test::sourcePath;

TEST_CASE("optimize: an impact gait returns to the shipped optimum from a perturbed start",
          "[optimize][impact_gait]") {
  const OptimizeConfig config =
      loadOptimizeConfig(sourcePath("configs/chevallereau_aoustin_0.75_impact.yaml"));
  const Parameterisation& par = config.options.parameterisation;
  REQUIRE(par.landing == Landing::ImpactSingleSupport);
  REQUIRE(par.ss_points == 3);
  const GaitFile shipped =
      loadGaitFile(sourcePath("configs/gait/chevallereau_aoustin_0.75_impact.yaml"));
  REQUIRE(shipped.options.parameterisation == par);
  const GaitEvaluator ev(config.robot, config.options, config.model_options);
  const GaitEvaluation<double> optimum = ev.evaluate(shipped.parameters);
  REQUIRE(optimum.defined());

  GaitParameters start = shipped.parameters;
  start(kStepLength) -= 0.01;
  start(par.impactSlopeIndex() + 1) += 0.1;  // δ4* at touchdown
  start(kTDS) = 0.3;                         // not read: must stay
  const OptimizationResult r = optimizeGait(ev, optimizationRequest(config, start));
  std::printf("  [impact_gait] optimize from a perturbed start: %s, C_Gamma %.6f (shipped %.6f), "
              "%d iterations, %.2f s\n",
              gaitopt::optimizationStatusName(r.status), r.evaluation.C_Gamma, optimum.C_Gamma, r.iterations,
              r.wall_time_s);
  CHECK(r.status == gaitopt::OptimizationStatus::Optimal);
  REQUIRE(r.evaluation.defined());
  CHECK(r.evaluation.C_Gamma == Approx(optimum.C_Gamma).epsilon(1e-3));
  CHECK(r.evaluation.speed == Approx(0.75).margin(1e-6));
  for (int i = 0; i < par.size(); ++i)
    if (!par.isUsed(i)) CHECK(r.parameters(i) == start(i));

  const LandingReport rep = landingReport(r.evaluation.motion.landing, par.landing,
                                          r.evaluation.alphadot_fSS);
  const LandingSolutions all = landingSolutions(ev.model(), rep, config.options.friction_coefficient);
  CHECK(all.status == "unique");
  CHECK(all.required_found);
}

TEST_CASE("optimize: the variables an impact then single support does not read are fixed",
          "[optimize][impact_gait]") {
  Parameterisation par;
  par.landing = Landing::ImpactSingleSupport;
  const GaitEvaluator ev(test::robotFile("rabbit_chevallereau_aoustin"), GaitOptions{});
  GaitParameters initial = GaitParameters::Constant(par.size(), -0.5);
  initial(kStepLength) = 0.4;
  initial(kTDS) = 0.1;
  const VariableSet v = gaitVariables(ev.model(), initial, par);
  int fixed = 0;
  for (int i = 0; i < par.size(); ++i) {
    INFO(par.names()[i]);
    if (par.isUsed(i)) {
      CHECK(v.lower(i) < v.upper(i));
    } else {
      ++fixed;
      CHECK(v.lower(i) == initial(i));
      CHECK(v.upper(i) == initial(i));
    }
  }
  CHECK(fixed == 7);
  CHECK(v.names[par.impactSlopeIndex()] == "delta3s_fSS");
}

TEST_CASE("optimize: an impact gait cannot start a zero-velocity landing optimisation",
          "[optimize][impact_gait]") {
  test::ScratchDir scratch("impact_optimize", "config");
  const std::string path = scratch.write(
      "robot: " + sourcePath("configs/robot/rabbit_chevallereau_aoustin.yaml") +
      "\ninitial_guess: " + sourcePath("configs/gait/chevallereau_aoustin_0.75_impact.yaml") +
      "\nparameterisation: {ss_points: 3, ds_points: 0}\n");
  test::requireConfigError(loadOptimizeConfig, path, "initial_guess", 2, "impact_ss");
}
