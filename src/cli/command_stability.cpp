// `gaitopt stability`: Poincaré analysis of the closed-loop gait (all DOF, and the 1-D map of
// the zero dynamics' α̇ at SS start).
#include <chrono>
#include <iostream>
#include <memory>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/stability_report.hpp"

namespace gaitopt::cli {
namespace {

struct StabilityArgs {
  std::string gait, out, jacobian = "sensitivity", ds_control = "cubic";
  bool quiet = false;
  StabilityRequest request;
};

}  // namespace

void registerStabilityCommand(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<StabilityArgs>();
  CLI::App* cmd = app.add_subcommand(
      "stability",
      "Poincare analysis of the closed-loop gait (gaitopt simulate's controller): fixed point, "
      "Jacobian on all DOF (variational equations or central differences), eigenvalues, power iteration (4.61), and the "
      "1-D map of alphad at SS start, the DS convergence zone of the time-optimal law (Fig. "
      "4.5). Writes OUT/stability.json, jacobian.csv, zero_dynamics_map.csv, ds_bounds.csv. "
      "Exit 3 if the cycle is unstable or not a fixed point.");
  cmd->add_option("--gait", a->gait, "Gait YAML file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", a->out, "Output directory")->required();
  cmd->add_option("--jacobian", a->jacobian,
                  "Poincare Jacobian: variational equations along the hybrid orbit "
                  "(sensitivity) or central differences of the map (fd)")
      ->capture_default_str()
      ->check(CLI::IsMember({"sensitivity", "fd"}));
  cmd->add_option("--fd-step", a->request.fd_step,
                  "Finite-difference step on every state component (--jacobian fd, power "
                  "iteration box)")
      ->capture_default_str()
      ->check(numberWithin(1e-9, 1e-1));
  cmd->add_option("--bandwidth", a->request.bandwidth, "Output bandwidth omega [rad/s]")
      ->capture_default_str()
      ->check(numberWithin(0.1, 1000.0, false, "rad/s"));
  cmd->add_option("--map-range", a->request.map_range, "Relative alphad range of the 1-D map (+-)")
      ->capture_default_str()
      ->check(numberWithin(0.0, 0.95));
  cmd->add_option("--margin-steps", a->request.margin_steps,
                  "Steps walked after a push, on a slope or with a payload (margins)")
      ->capture_default_str()
      ->check(integerWithin(1, 100));
  cmd->add_option("--map-points", a->request.map_points, "Points of the 1-D map")
      ->capture_default_str()
      ->check(integerWithin(2, 10001));
  addDsControlOption(cmd, a->ds_control);
  cmd->add_option("--ds-range", a->request.ds_range,
                  "Relative alphad_fDS range of the DS convergence-zone study (Fig. 4.5, +-)")
      ->capture_default_str()
      ->check(numberWithin(0.0, 0.95));
  cmd->add_option("--ds-points", a->request.ds_points, "Points of the DS convergence-zone study")
      ->capture_default_str()
      ->check(integerWithin(2, 10001));
  cmd->add_flag("--quiet", a->quiet, "No progress lines");
  cmd->callback([a, &exit_code]() {
    const GaitFile gait = loadGaitFile(a->gait);
    OutputTransaction output({{"--gait", a->gait}});
    const std::string dir = output.directory(
        "--out", a->out,
        ourFiles({"stability.json", "jacobian.csv", "zero_dynamics_map.csv", "ds_bounds.csv"}));
    const GaitEvaluator ev(gait.robot, gait.options, gait.model_options);
    const GaitEvaluation<double> e = ev.evaluate(gait.parameters);
    if (!e.defined() || !e.motion_computed) {
      std::cerr << "gaitopt: error: " << a->gait << ": the step is undefined\n";
      exit_code = kExitUndefined;
      return;
    }
    StabilityRequest& req = a->request;
    req.jacobian = a->jacobian == "fd" ? PoincareJacobianMethod::FiniteDifference
                                       : PoincareJacobianMethod::Sensitivity;
    req.ds_control = dsAlphaControlOf(a->ds_control);
    const auto start = std::chrono::steady_clock::now();
    if (!a->quiet)
      req.on_stage = [start](const std::string& stage, int k, int n) {
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::cout << "stability [" << k << "/" << n << "] " << stage << "  "
                  << elapsedAndRemaining(elapsed, 0, n) << "\n" << std::flush;
      };
    const StabilityStudy s =
        studyStability(e, gait.robot, gait.options, gait.model_options, req);
    writeStabilityReport(dir, s, req, a->gait);
    output.commit();
    if (!s.jacobian_fallback.empty())
      std::cerr << "gaitopt: stability: note: Jacobian by central differences; the variational "
                   "equations stopped ("
                << s.jacobian_fallback << ")\n";
    std::cout << "stability: dominant |eigenvalue| " << shortNumber(s.dominant_modulus)
              << ", power iteration " << shortNumber(s.power_estimate) << ", fixed-point residual "
              << shortNumber(s.linearisation.fixed_point_residual)
              << (s.stable_cycle ? ", stable" : ", NOT stable") << " -> " << a->out << "\n";
    exit_code = s.stable_cycle ? 0 : kExitUndefined;
  });
}

}  // namespace gaitopt::cli
