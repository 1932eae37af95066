// Full Poincaré analysis of the default gait's closed-loop cycle (gaitopt stability without
// the 1-D map): Jacobian on all 10 state components by central differences (20 steps
// simulated) plus 6 power iterations (4.61), CVODE tolerances 1e-12/1e-14. Target ≤ 2 s.
#include <cstdio>

#include "bench_timing.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/sim/poincare.hpp"

using namespace gaitopt;
using namespace gaitopt::bench;

int main(int argc, char** argv) {
  BatchOptions opts;
  opts.repeats = 11;
  if (const auto status = parseBatchOptions(argc, argv, "bench_stability", 1, opts)) return *status;
  const GaitFile gait = loadGaitFile(GAITOPT_SOURCE_DIR "/configs/gait/default_step.yaml");
  const GaitEvaluator ev(gait.robot, gait.options, gait.model_options);
  const GaitEvaluation<double> e = ev.evaluate(gait.parameters);
  const Model model = buildModel(gait.robot, gait.model_options);
  WalkRequest req;
  req.tolerances = {1e-12, 1e-14};
  const StepMap P = walkingStepMap(e, model, model, req);
  const Eigen::VectorXd x = walkingCycleState(e.motion);
  const Eigen::VectorXd h = Eigen::VectorXd::Constant(10, 1e-4);
  const Environment env;
  printEnvironment("bench_stability", env);
  double dominant = 0.0;
  const Stats s = measure("poincare_analysis", "linearisePoincare + 6 power iterations",
                          opts.batch, opts.repeats, [&]() {
                            const PoincareLinearisation L = linearisePoincare(P, x, h);
                            Eigen::VectorXd v;
                            dominant = std::abs(L.eigenvalues(0));
                            return dominant + powerIteration(P, x, h, 6, v);
                          });
  std::printf("dominant |eigenvalue| %.3g\n", dominant);
  std::printf("Poincare analysis: median %.3f s (min %.3f, p90 %.3f), target 2 s: %s\n",
              s.median_ns * 1e-9, s.min_ns * 1e-9, s.p90_ns * 1e-9,
              verdict(s.median_ns * 1e-9, 2.0));
  if (!opts.json_path.empty()) {
    JsonWriter w;
    w.beginObject();
    writeEnvironment(w, "bench_stability", env);
    w.key("results").beginArray().beginObject();
    writeStatsFields(w, s);
    w.endObject().endArray().endObject();
    if (!writeJsonReport("bench_stability", opts.json_path, w)) return 1;
  }
  return 0;
}
