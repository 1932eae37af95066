// bench_gait: wall-clock cost of one gait evaluation (GaitEvaluator::evaluate: constraints,
// criteria, motion) and of one evaluation with the exact gradient (evaluateWithGradient: the
// double pass plus the forward-AD pass with 17 directions; with and without the derivatives of
// the DS piece samples, which only the DS between-node rows need), on the default robot
// (configs/robot/rabbit_miossec.yaml) with default GaitOptions, as the optimiser calls it for a
// C_Γ objective (criteria_refinement 1: W and C_E on the SS grid); and both again with the
// default criteria_refinement 2 (W and C_E sampled on the twice finer SS grid), as
// `gaitopt evaluate` and the written results use it.
//
//   bench_gait [--json FILE] [--batch N] [--repeats N] [--help]
//
// Parameter sets: the defined step of the tests (tests/test_gait_support.hpp) and, when the file
// exists and holds the 17 named parameters, configs/gait/default_step.yaml (skipped otherwise).
// Each measurement times `batch` consecutive calls (default 10) and repeats that `repeats` times
// (default 51, at least 31 recommended) after one untimed warm-up batch. Reported per call: the
// median, the minimum and the 90th percentile over the repeated batches, against the targets
// evaluate ≤ 200 µs and evaluateWithGradient ≤ 2 ms (medians).
//
// Dead-code elimination is prevented twice: every result object escapes through an empty asm
// statement with a memory clobber, and one criterion per call is accumulated into a volatile
// sink (bench_timing.hpp).
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/io/robot_file.hpp"

namespace {

using namespace gaitopt;
using namespace gaitopt::bench;

constexpr const char* kRobotFile = GAITOPT_SOURCE_DIR "/configs/robot/rabbit_miossec.yaml";
constexpr const char* kStepFile = GAITOPT_SOURCE_DIR "/configs/gait/default_step.yaml";
constexpr double kEvaluateTargetNs = 200e3;  // 200 µs
constexpr double kGradientTargetNs = 2e6;    // 2 ms

// The defined step of tests/test_gait_support.hpp (levels 0–4 hold), kGaitParameterNames order.
GaitParameters definedStep() {
  GaitParameters p(kNumGaitParameters);
  p << -0.044819, -2.593492, 1.520796, 0.35, -0.190837, -2.495513, 1.520796, -2.445513,
      1.520796, 0.0, 0.06, -0.9, 0.3, 0.3, 0.3, 0.3, 0.12;
  return p;
}

// The 17 parameters from a mapping that names all of them (plain numbers), or nothing.
std::optional<GaitParameters> parametersIn(const YAML::Node& map) {
  if (!map.IsMap()) return std::nullopt;
  GaitParameters p(kNumGaitParameters);
  for (int i = 0; i < kNumGaitParameters; ++i) {
    const YAML::Node v = map[kGaitParameterNames[i]];
    if (!v || !v.IsScalar()) return std::nullopt;
    try {
      p(i) = v.as<double>();
    } catch (const YAML::Exception&) {
      return std::nullopt;
    }
    if (!std::isfinite(p(i))) return std::nullopt;
  }
  return p;
}

// The step of a gait file whose layout this benchmark does not own: the named parameters at the
// top level or in a nested mapping (e.g. `parameters:`), searched breadth-first, two levels deep.
std::optional<GaitParameters> findParameters(const YAML::Node& root) {
  std::vector<YAML::Node> level = {root};
  for (int depth = 0; depth <= 2 && !level.empty(); ++depth) {
    std::vector<YAML::Node> next;
    for (const YAML::Node& node : level) {
      if (const auto p = parametersIn(node)) return p;
      if (node.IsMap())
        for (const auto& kv : node)
          if (kv.second.IsMap()) next.push_back(kv.second);
    }
    level = std::move(next);
  }
  return std::nullopt;
}

struct StepSet {
  std::string name;
  std::string source;
  GaitParameters p;
};

// The parameter sets to time; `note` explains a skipped shipped step.
std::vector<StepSet> stepSets(std::string& note) {
  std::vector<StepSet> sets = {{"defined_step", "built in (tests/test_gait_support.hpp)",
                                definedStep()}};
  if (!std::ifstream(kStepFile).good()) {
    note = "configs/gait/default_step.yaml absent: skipped";
    return sets;
  }
  try {
    if (const auto p = findParameters(YAML::LoadFile(kStepFile))) {
      sets.push_back({"default_step_yaml", kStepFile, *p});
      note = "configs/gait/default_step.yaml: timed";
    } else {
      note = "configs/gait/default_step.yaml holds no mapping of the 17 parameters: skipped";
    }
  } catch (const YAML::Exception& e) {
    note = std::string("configs/gait/default_step.yaml unreadable (") + e.what() + "): skipped";
  }
  return sets;
}

struct Measured {
  StepSet set;
  int failed_level = -1;
  bool motion_computed = false;
  double C_Gamma = 0.0;
  Stats evaluate, gradient, gradient_nodes, evaluate_refined, gradient_refined;
};

}  // namespace

int main(int argc, char** argv) {
  BatchOptions opts;
  if (const auto status = parseBatchOptions(argc, argv, "bench_gait", 10, opts)) return *status;
  const int batch = opts.batch, repeats = opts.repeats;

  std::optional<GaitEvaluator> evaluator;
  try {
    evaluator.emplace(loadRobot(kRobotFile), GaitOptions());
  } catch (const std::exception& e) {
    std::cerr << "bench_gait: error: " << e.what() << "\n";
    return 2;
  }
  const GaitEvaluator& refined = *evaluator;
  const GaitEvaluator ev = refined.withCriteriaRefinement(1);  // the optimiser's (C_Γ objective)
  std::string step_note;
  const std::vector<StepSet> sets = stepSets(step_note);
  const Environment env;

  printEnvironment("bench_gait", env);
  std::printf("robot:     %s\n", kRobotFile);
  std::printf("options:   default GaitOptions (ss_nodes %d, ds_nodes %d, %zu constraints)\n",
              ev.options().ss_nodes, ev.options().ds_nodes,
              static_cast<std::size_t>(ev.layout().size()));
  std::printf("steps:     %s\n", step_note.c_str());
  std::printf("timing:    %d batches of %d calls (+1 warm-up batch), steady_clock\n\n", repeats,
              batch);

  std::vector<Measured> results;
  for (const StepSet& set : sets) {
    Measured m;
    m.set = set;
    const GaitEvaluation<double> e = ev.evaluate(set.p);
    m.failed_level = e.failed_level;
    m.motion_computed = e.motion_computed;
    m.C_Gamma = e.C_Gamma;
    const GaitParameters p = set.p;
    const auto values = [&p](const GaitEvaluator& e) {
      return [&e, &p]() {
        const GaitEvaluation<double> r = e.evaluate(p);
        escape(r);
        return r.C_Gamma + r.g[0];
      };
    };
    const auto gradient = [&p](const GaitEvaluator& e, bool ds_pieces) {
      return [&e, &p, ds_pieces]() {
        const GaitGradient r = e.evaluateWithGradient(p, ds_pieces);
        escape(r);
        return r.dC_Gamma(0) + r.dg(0, 3);
      };
    };
    m.evaluate = measure("evaluate", "GaitEvaluator::evaluate (values), double", batch, repeats,
                         values(ev));
    m.gradient = measure("evaluateWithGradient",
                         "values + exact gradient (forward AD, 17 directions)", batch, repeats,
                         gradient(ev, true));
    m.gradient_nodes = measure("gradient, no DS pieces",
                               "as evaluateWithGradient without the DS piece derivatives (the "
                               "optimiser while the DS between-node rows are off)",
                               batch, repeats, gradient(ev, false));
    m.evaluate_refined = measure("evaluate, W/C_E x2", "evaluate with criteria_refinement 2",
                                 batch, repeats, values(refined));
    m.gradient_refined = measure("gradient, W/C_E x2",
                                 "evaluateWithGradient with criteria_refinement 2", batch,
                                 repeats, gradient(refined, true));
    results.push_back(m);
  }

  std::printf("%-20s %-22s %12s %12s %12s %10s  %s\n", "step", "measurement (us/call)", "median",
              "min", "p90", "target", "");
  std::printf("%-20s %-22s %12s %12s %12s %10s\n", "--------------------",
              "----------------------", "------------", "------------", "------------",
              "----------");
  for (const Measured& m : results) {
    const auto row = [&m](const Stats& s, double target_ns) {
      std::printf("%-20s %-22s %12.1f %12.1f %12.1f %10.0f  %s\n", m.set.name.c_str(),
                  s.name.c_str(), s.median_ns * 1e-3, s.min_ns * 1e-3, s.p90_ns * 1e-3,
                  target_ns * 1e-3, verdict(s.median_ns, target_ns));
    };
    row(m.evaluate, kEvaluateTargetNs);
    row(m.gradient, kGradientTargetNs);
    row(m.gradient_nodes, kGradientTargetNs);
    row(m.evaluate_refined, kEvaluateTargetNs);
    row(m.gradient_refined, kGradientTargetNs);
  }
  for (const Measured& m : results)
    std::printf("\n%s: failed_level %d, motion computed %s, C_Gamma %.6g", m.set.name.c_str(),
                m.failed_level, m.motion_computed ? "yes" : "no", m.C_Gamma);
  std::printf("\n\n(sink %g)\n", static_cast<double>(g_sink));

  if (!opts.json_path.empty()) {
    JsonWriter w;
    w.beginObject();
    writeEnvironment(w, "bench_gait", env);
    w.key("robot").value(std::string(kRobotFile));
    w.key("ss_nodes").value(ev.options().ss_nodes);
    w.key("ds_nodes").value(ev.options().ds_nodes);
    w.key("batch").value(batch);
    w.key("repeats").value(repeats);
    w.key("steps_note").value(step_note);
    w.key("unit").value("ns per call");
    w.key("results").beginArray();
    for (const Measured& m : results) {
      const auto emit = [&w, &m](const Stats& s, double target_ns) {
        w.beginObject();
        w.key("step").value(m.set.name);
        w.key("step_source").value(m.set.source);
        w.key("parameters").value(m.set.p);
        w.key("failed_level").value(m.failed_level);
        writeStatsFields(w, s);
        w.key("target_ns").value(target_ns);
        w.key("target_met").value(s.median_ns <= target_ns);
        w.endObject();
      };
      emit(m.evaluate, kEvaluateTargetNs);
      emit(m.gradient, kGradientTargetNs);
      emit(m.gradient_nodes, kGradientTargetNs);
      emit(m.evaluate_refined, kEvaluateTargetNs);
      emit(m.gradient_refined, kGradientTargetNs);
    }
    w.endArray();
    w.endObject();
    if (!writeJsonReport("bench_gait", opts.json_path, w)) return 1;
  }
  return 0;
}
