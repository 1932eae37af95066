#include "gaitopt/io/optimize_output.hpp"

#include <filesystem>

#include "gaitopt/io/atomic_file.hpp"
#include "gaitopt/gait/summary.hpp"
#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/io/gait_file.hpp"

namespace gaitopt {

namespace fs = std::filesystem;

void writeSolverJson(JsonWriter& w, const SolverSettings& s, const OptimizationResult& r) {
  w.key("solver").beginObject();
  w.key("backend").value(backendName(s.backend));
  w.key("hierarchy").value(strategyName(s.hierarchy));
  w.key("status").value(r.status);
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
  writeFileAtomically((d / "summary.json").string(), outputs.summary_json);
  writeFileAtomically((d / "gait.yaml").string(), outputs.gait_yaml);
  if (outputs.trajectory_csv) {
    writeFileAtomically((d / "trajectory.csv").string(), *outputs.trajectory_csv);
  }
}

}  // namespace gaitopt
