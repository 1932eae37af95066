// Poincaré analysis of the default gait's closed-loop cycle (CVODE tolerances 1e-12/1e-14):
// the Jacobian on all 10 state components by the variational equations (one step with
// sensitivities) and by central differences (20 steps), and the full analysis of
// `gaitopt stability` with its defaults: sensitivity Jacobian, 6 power iterations (4.61) and the
// zero-dynamics study (61 starts). Target for the full analysis ≤ 2 s.
#include <cstdio>
#include <ctime>

#include "bench_timing.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/sim/poincare_sensitivity.hpp"
#include "gaitopt/sim/zero_dynamics_map.hpp"

using namespace gaitopt;
using namespace gaitopt::bench;

int main(int argc, char** argv) {
  BatchOptions opts;
  opts.repeats = 5;
  if (const auto status = parseBatchOptions(argc, argv, "bench_stability", 1, opts)) return *status;
  const GaitFile gait = loadGaitFile(GAITOPT_SOURCE_DIR "/configs/gait/default_step.yaml");
  const GaitEvaluator ev(gait.robot, gait.options, gait.model_options);
  const GaitEvaluation<double> e = ev.evaluate(gait.parameters);
  const Model model = buildModel(gait.robot, gait.model_options);
  WalkRequest req;
  req.tolerances = {1e-12, 1e-14};
  req.torque_limits = false;  // the analysis's smooth closed loop (gaitopt stability)
  const StepMap P = walkingStepMap(e, model, model, req);
  const Eigen::VectorXd x = walkingCycleState(e.motion);
  const Eigen::VectorXd h = Eigen::VectorXd::Constant(10, 1e-4);
  const Environment env;
  printEnvironment("bench_stability", env);
  double fd_dominant = 0.0, sens_dominant = 0.0;
  const Stats fd = measure("jacobian_fd", "linearisePoincare: central differences, 20 steps",
                           opts.batch, opts.repeats, [&]() {
                             fd_dominant = std::abs(linearisePoincare(P, x, h).eigenvalues(0));
                             return fd_dominant;
                           });
  const Stats sens = measure("jacobian_sensitivity",
                             "linearisePoincareBySensitivity: variational equations, 1 step",
                             opts.batch, opts.repeats, [&]() {
                               sens_dominant = std::abs(
                                   linearisePoincareBySensitivity(e, model, model, req, x)
                                       .eigenvalues(0));
                               return sens_dominant;
                             });
  // CPU time as well: on a shared machine the wall-clock median overstates the cost.
  const std::clock_t cpu0 = std::clock();
  const Stats full = measure(
      "poincare_analysis", "sensitivity Jacobian + 6 power iterations + zero-dynamics study",
      opts.batch, opts.repeats, [&]() {
        const PoincareLinearisation L = linearisePoincareBySensitivity(e, model, model, req, x);
        Eigen::VectorXd v;
        const double c = powerIteration(P, x, h, 6, v);
        return std::abs(L.eigenvalues(0)) + c +
               studyZeroDynamics(e, model, model, req, ZeroDynamicsRequest{}).slope;
      });
  const double cpu_per_call = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC /
                              (opts.batch * (opts.repeats + 1));  // + the warm-up batch
  std::printf("full analysis: %.3f s CPU per call\n", cpu_per_call);
  std::printf("dominant |eigenvalue|: sensitivity %.3g, finite differences %.3g\n",
              sens_dominant, fd_dominant);
  std::printf("Jacobian: sensitivity median %.3f s, finite differences median %.3f s\n",
              sens.median_ns * 1e-9, fd.median_ns * 1e-9);
  std::printf("Poincare analysis: median %.3f s (min %.3f, p90 %.3f), target 2 s: %s\n",
              full.median_ns * 1e-9, full.min_ns * 1e-9, full.p90_ns * 1e-9,
              verdict(full.median_ns * 1e-9, 2.0));
  if (!opts.json_path.empty()) {
    JsonWriter w;
    w.beginObject();
    writeEnvironment(w, "bench_stability", env);
    w.key("results").beginArray();
    for (const Stats* s : {&fd, &sens, &full}) {
      w.beginObject();
      writeStatsFields(w, *s);
      w.endObject();
    }
    w.endArray().endObject();
    if (!writeJsonReport("bench_stability", opts.json_path, w)) return 1;
  }
  return 0;
}
