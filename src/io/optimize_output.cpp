#include "gaitopt/io/optimize_output.hpp"

#include <filesystem>
#include <optional>

#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/summary_file.hpp"
#include "gaitopt/io/trajectory_file.hpp"
#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/opt/result_order.hpp"

namespace gaitopt {

namespace fs = std::filesystem;

void writeSolverJson(JsonWriter& w, const SolverSettings& s, const OptimizationResult& r) {
  w.key("solver").beginObject();
  w.key("backend").value(backendName(s.backend));
  w.key("hierarchy").value(strategyName(s.hierarchy));
  w.key("status").value(optimizationStatusName(r.status));
  w.key("iterations").value(r.iterations);
  w.key("function_evaluations").value(r.function_evaluations);
  w.key("gradient_evaluations").value(r.gradient_evaluations);
  w.key("wall_time_s").value(r.wall_time_s);
  w.key("constraint_violation").value(r.constraint_violation);
  w.key("unmet_level");
  if (r.unmet_level < 0) {
    w.null();
  } else {
    w.value(r.unmet_level);
  }
  w.key("unmet_constraints").beginArray();
  for (const std::string& name : r.unmet_constraints) w.value(name);
  w.endArray();
  w.key("stages").beginArray();
  for (const StageReport& stage : r.stages) {
    w.beginObject();
    w.key("name").value(stage.name);
    w.key("status").value(nlpStatusName(stage.status));
    w.key("iterations").value(stage.iterations);
    w.endObject();
  }
  w.endArray();
  w.endObject();
}

std::string robotPathFrom(const std::string& dir, const std::string& robot_path) {
  const fs::path robot = fs::absolute(robot_path);
  std::error_code ec;
  const fs::path rel = fs::relative(robot, fs::absolute(dir), ec);
  return ec || rel.empty() ? robot.lexically_normal().generic_string() : rel.generic_string();
}

OptimizationOutputs optimizationOutputs(const GaitEvaluator& evaluator,
                                        const OptimizeConfig& config, const OptimizationResult& r,
                                        const std::string& dir,
                                        const std::function<void(JsonWriter&)>& extra) {
  const GaitEvaluation<double>& e = r.evaluation;
  OptimizationOutputs out;
  out.summary_json = gaitSummaryJson(evaluator, r.parameters, e, [&](JsonWriter& w) {
    w.key("criterion").value(criterionName(config.criterion));
    writeSolverJson(w, config.solver, r);
    writeOverridesJson(w, config.overrides);
    if (extra) extra(w);
  });
  out.gait_yaml = gaitYaml(robotPathFrom(dir, config.robot_path), r.parameters, config.options,
                           config.model_options);
  if (e.defined() && e.motion_computed)
    out.trajectory_csv = trajectoryCsv(sampleTrajectory(evaluator, e, config.options.sample_rate));
  return out;
}

void writeOptimizationOutputs(const std::string& dir, const OptimizationOutputs& outputs) {
  const fs::path d(dir);
  // Only the leaf: after an interrupt has removed a staging directory, a sweep worker must not
  // bring it back by creating its parents (the temporary would outlive the run).
  std::error_code ec;
  if (!fs::create_directory(d, ec) && ec) {
    throw std::runtime_error("cannot create '" + dir + "': " + ec.message());
  }
  writeNewFile((d / "summary.json").string(), outputs.summary_json);
  writeNewFile((d / "gait.yaml").string(), outputs.gait_yaml);
  if (outputs.trajectory_csv) {
    writeNewFile((d / "trajectory.csv").string(), *outputs.trajectory_csv);
  }
}

namespace {

void numberOrNull(JsonWriter& w, const std::optional<double>& v) {
  if (v) {
    w.value(*v);
  } else {
    w.null();
  }
}

void writeRuns(JsonWriter& w, const std::vector<StartRun>& runs, Criterion c) {
  w.key("runs").beginArray();
  for (const StartRun& run : runs) {
    w.beginObject();
    w.key("start").value(run.start);
    w.key("status").value(optimizationStatusName(run.result.status));
    w.key("criterion");
    numberOrNull(w, resultCriterion(run.result, c));
    w.key("iterations").value(run.result.iterations);
    w.key("wall_time_s").value(run.result.wall_time_s);
    w.key("unmet_level");
    if (run.result.unmet_level < 0) {
      w.null();
    } else {
      w.value(run.result.unmet_level);
    }
    w.endObject();
  }
  w.endArray();
}

}  // namespace

void writeRandomStartsJson(JsonWriter& w, const std::vector<StartRun>& runs, std::uint64_t seed,
                           int best_start, Criterion c) {
  const StartsSummary s = summarizeStarts(runs, c);
  w.key("random_starts").beginObject();
  w.key("count").value(static_cast<int>(runs.size()));
  w.key("seed").value(static_cast<double>(seed));
  w.key("converged").value(s.converged);
  w.key("criterion_min");
  numberOrNull(w, s.min);
  w.key("criterion_max");
  numberOrNull(w, s.max);
  w.key("spread");
  numberOrNull(w, s.min ? std::optional<double>(*s.max - *s.min) : std::nullopt);
  w.key("best_start").value(best_start);
  writeRuns(w, runs, c);
  w.endObject();
}

void writeGlobalSearchJson(JsonWriter& w, const GlobalSearchResult& g,
                           const std::vector<StartRun>& runs, std::uint64_t seed, Criterion c) {
  w.key("global").beginObject();
  w.key("count").value(static_cast<int>(g.starts.size()));
  w.key("seed").value(static_cast<double>(seed));
  w.key("optimised").value(static_cast<int>(runs.size()));
  w.key("skipped").value(g.skipped);
  w.key("converged").value(g.converged);
  w.key("median_time_per_start_s").value(g.median_time_per_start_s);
  w.key("best_start").value(g.best_start);
  w.key("clusters").beginArray();
  for (const OptimumCluster& cl : g.clusters) {
    w.beginObject();
    w.key("criterion").value(cl.criterion);
    w.key("size").value(cl.size());
    w.key("starts").beginArray();
    for (int m : cl.members) w.value(m);
    w.endArray();
    w.endObject();
  }
  w.endArray();
  writeRuns(w, runs, c);
  w.endObject();
}

}  // namespace gaitopt
