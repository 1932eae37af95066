// Closed-loop hybrid walking benchmark: 20 steps with gaitopt simulate's controller (torque
// projection on) on the nominal model, samples at 200 Hz, of (1) the default gait (configs/
// gait/default_step.yaml: zero-velocity landing, DS) and (2) the impact-landing gait
// (configs/gait/chevallereau_aoustin_0.75_impact.yaml: algebraic impact, no DS).
// Target: ≤ 0.5 s per 20-step simulation (median).
#include <cstdio>
#include <iostream>
#include <vector>

#include "bench_timing.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/sim/hybrid_walk.hpp"
#include "gaitopt/sim/impact_touchdown.hpp"

using namespace gaitopt;
using namespace gaitopt::bench;

namespace {

struct Case {
  const char* name;
  const char* file;
};

}  // namespace

int main(int argc, char** argv) {
  BatchOptions opts;
  if (const auto status = parseBatchOptions(argc, argv, "bench_simulate", 1, opts)) return *status;
  const Environment env;
  printEnvironment("bench_simulate", env);
  std::vector<Stats> all;
  bool ok = true;
  for (const Case c :
       {Case{"simulate_20_steps", "configs/gait/default_step.yaml"},
        Case{"simulate_20_steps_impact", "configs/gait/chevallereau_aoustin_0.75_impact.yaml"}}) {
    const GaitFile gait = loadGaitFile(std::string(GAITOPT_SOURCE_DIR "/") + c.file);
    const GaitEvaluator ev(gait.robot, gait.options, gait.model_options);
    const GaitEvaluation<double> e = ev.evaluate(gait.parameters);
    const Model model = buildModel(gait.robot, gait.model_options);
    WalkRequest req;
    req.steps = 20;
    configureForGait(gait.options, req);
    const TouchdownMap td = gaitTouchdown(gait.options, "auto", gait.options.friction_coefficient);
    const WalkResult check = simulateWalk(e, model, model, req, td);
    std::printf("gait:      %s, 20 steps, outcome %s\n", c.file, outcomeName(check.outcome));
    ok = ok && check.outcome == WalkOutcome::Completed;
    const Stats s = measure(c.name, std::string("simulateWalk, 20 steps, nominal plant, ") + c.file,
                            opts.batch, opts.repeats, [&]() {
                              const WalkResult r = simulateWalk(e, model, model, req, td);
                              return r.steps.back().alphad_start;
                            });
    std::printf("%s: median %.4f s (min %.4f, p90 %.4f), target 0.5 s: %s\n", c.name,
                s.median_ns * 1e-9, s.min_ns * 1e-9, s.p90_ns * 1e-9,
                verdict(s.median_ns * 1e-9, 0.5));
    all.push_back(s);
  }
  if (!opts.json_path.empty()) {
    JsonWriter w;
    w.beginObject();
    writeEnvironment(w, "bench_simulate", env);
    w.key("results").beginArray();
    for (const Stats& s : all) {
      w.beginObject();
      writeStatsFields(w, s);
      w.endObject();
    }
    w.endArray().endObject();
    if (!writeJsonReport("bench_simulate", opts.json_path, w)) return 1;
  }
  return ok ? 0 : 1;
}
