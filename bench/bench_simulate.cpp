// Closed-loop hybrid walking benchmark: 20 steps of the default gait (configs/gait/
// default_step.yaml) with gaitopt simulate's controller on the nominal model, samples at
// 200 Hz. Target: ≤ 0.5 s per 20-step simulation (median).
#include <cstdio>
#include <iostream>

#include "bench_timing.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/sim/hybrid_walk.hpp"

using namespace gaitopt;
using namespace gaitopt::bench;

int main(int argc, char** argv) {
  BatchOptions opts;
  if (const auto status = parseBatchOptions(argc, argv, "bench_simulate", 1, opts)) return *status;
  const GaitFile gait = loadGaitFile(GAITOPT_SOURCE_DIR "/configs/gait/default_step.yaml");
  const GaitEvaluator ev(gait.robot, gait.options, gait.model_options);
  const GaitEvaluation<double> e = ev.evaluate(gait.parameters);
  const Model model = buildModel(gait.robot, gait.model_options);
  WalkRequest req;
  req.steps = 20;
  const WalkResult check = simulateWalk(e, model, model, req);
  const Environment env;
  printEnvironment("bench_simulate", env);
  std::printf("gait:      configs/gait/default_step.yaml, 20 steps, outcome %s\n",
              outcomeName(check.outcome));
  const Stats s = measure("simulate_20_steps", "simulateWalk, 20 steps, nominal plant",
                          opts.batch, opts.repeats, [&]() {
                            const WalkResult r = simulateWalk(e, model, model, req);
                            return r.steps.back().alphad_start;
                          });
  std::printf("simulate 20 steps: median %.4f s (min %.4f, p90 %.4f), target 0.5 s: %s\n",
              s.median_ns * 1e-9, s.min_ns * 1e-9, s.p90_ns * 1e-9,
              verdict(s.median_ns * 1e-9, 0.5));
  if (!opts.json_path.empty()) {
    JsonWriter w;
    w.beginObject();
    writeEnvironment(w, "bench_simulate", env);
    w.key("results").beginArray().beginObject();
    writeStatsFields(w, s);
    w.endObject().endArray().endObject();
    if (!writeJsonReport("bench_simulate", opts.json_path, w)) return 1;
  }
  return check.outcome == WalkOutcome::Completed ? 0 : 1;
}
