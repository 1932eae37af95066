// bench_impact_gait: cost of the gaits that land with an impact (docs/science/impact-gaits.md):
// one evaluation and one evaluation with the exact gradient (AD through the impact map) of the
// shipped C&A impact step (configs/gait/chevallereau_aoustin_0.75_impact.yaml), and the wall
// time of the whole optimisation configs/chevallereau_aoustin_0.75_impact.yaml (staged SLSQP
// from the default initial guess).
//
//   bench_impact_gait [--json FILE] [--batch N] [--repeats N] [--help]
//
// Evaluations: `repeats` batches of `batch` calls (default 10) after a warm-up batch; the
// optimisation: max(3, repeats / 10) complete runs (batch 1). Reported: medians, minima, p90.
#include <cstdio>
#include <exception>
#include <iostream>
#include <optional>
#include <string>

#include "bench_timing.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/opt/optimizer.hpp"

namespace {

using namespace gaitopt;
using namespace gaitopt::bench;

constexpr const char* kStepFile =
    GAITOPT_SOURCE_DIR "/configs/gait/chevallereau_aoustin_0.75_impact.yaml";
constexpr const char* kConfigFile =
    GAITOPT_SOURCE_DIR "/configs/chevallereau_aoustin_0.75_impact.yaml";

void row(const Stats& s, double scale, const char* unit) {
  std::printf("%-34s %12.3f %12.3f %12.3f  %s\n", s.name.c_str(), s.median_ns * scale,
              s.min_ns * scale, s.p90_ns * scale, unit);
}

}  // namespace

int main(int argc, char** argv) {
  BatchOptions opts;
  if (const auto status = parseBatchOptions(argc, argv, "bench_impact_gait", 10, opts))
    return *status;
  std::optional<GaitFile> step;
  std::optional<OptimizeConfig> config;
  try {
    step.emplace(loadGaitFile(kStepFile));
    config.emplace(loadOptimizeConfig(kConfigFile));
  } catch (const std::exception& e) {
    std::cerr << "bench_impact_gait: error: " << e.what() << "\n";
    return 2;
  }
  const GaitEvaluator ev(step->robot, step->options, step->model_options);
  const GaitParameters p = step->parameters;
  const GaitEvaluation<double> e = ev.evaluate(p);
  const Environment env;
  printEnvironment("bench_impact_gait", env);
  std::printf("step:      %s (%s, %d parameters, C_Gamma %.6g, failed_level %d)\n", kStepFile,
              ev.options().parameterisation.label().c_str(), ev.numParameters(), e.C_Gamma,
              e.failed_level);
  std::printf("config:    %s\n\n", kConfigFile);

  const Stats evaluate = measure("evaluate", "GaitEvaluator::evaluate, impact step", opts.batch,
                                 opts.repeats, [&ev, &p]() {
                                   const GaitEvaluation<double> r = ev.evaluate(p);
                                   escape(r);
                                   return r.C_Gamma;
                                 });
  const Stats gradient = measure("evaluateWithGradient", "values + exact gradient, impact step",
                                 opts.batch, opts.repeats, [&ev, &p]() {
                                   const GaitGradient r = ev.evaluateWithGradient(p);
                                   escape(r);
                                   return r.dC_Gamma(0);
                                 });
  const GaitEvaluator opt_ev(config->robot, config->options, config->model_options);
  const OptimizationRequest request =
      optimizationRequest(*config, configuredInitialGuess(*config, opt_ev.model()));
  double best = 0.0;
  std::string status;
  const Stats optimise = measure("optimizeGait", "C&A impact gait, 0.75 m/s, C_Gamma", 1,
                                 std::max(3, opts.repeats / 10), [&]() {
                                   const OptimizationResult r = optimizeGait(opt_ev, request);
                                   best = r.evaluation.C_Gamma;
                                   status = optimizationStatusName(r.status);
                                   return best;
                                 });
  std::printf("%-34s %12s %12s %12s\n", "measurement", "median", "min", "p90");
  row(evaluate, 1e-3, "us/call");
  row(gradient, 1e-3, "us/call");
  row(optimise, 1e-9, "s/run");
  std::printf("\noptimisation: %s, C_Gamma %.6g\n(sink %g)\n", status.c_str(), best,
              static_cast<double>(g_sink));

  if (!opts.json_path.empty()) {
    JsonWriter w;
    w.beginObject();
    writeEnvironment(w, "bench_impact_gait", env);
    w.key("step").value(std::string(kStepFile));
    w.key("config").value(std::string(kConfigFile));
    w.key("unit").value("ns");
    w.key("results").beginArray();
    for (const Stats* s : {&evaluate, &gradient, &optimise}) {
      w.beginObject();
      writeStatsFields(w, *s);
      w.endObject();
    }
    w.endArray();
    w.key("optimisation_status").value(status);
    w.key("optimisation_C_Gamma").value(best);
    w.endObject();
    if (!writeJsonReport("bench_impact_gait", opts.json_path, w)) return 1;
  }
  return 0;
}
