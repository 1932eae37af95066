// `gaitopt stability`: Poincaré analysis of the closed-loop gait (all DOF, and the 1-D map of
// the zero dynamics' α̇ at SS start).
#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/io/atomic_file.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/sim/poincare.hpp"

namespace gaitopt::cli {
namespace {

namespace fs = std::filesystem;

struct StabilityArgs {
  std::string gait, out;
  double step = 1e-4, bandwidth = 40.0, range = 0.3;
  int points = 61;
};

struct MapPoint {
  double alphad, next;
  std::string outcome;
};

// α̇_iSS(k) → α̇_iSS(k + 1) on the virtual constraints (§4.2.2, with this DS controller).
std::vector<MapPoint> zeroDynamicsMap(const StepMap& P, const Eigen::VectorXd& x, double range,
                                      int points) {
  std::vector<MapPoint> out;
  for (int i = 0; i < points; ++i) {
    const double alphad = x(5) * (1.0 + range * (2.0 * i / (points - 1) - 1.0));
    Eigen::VectorXd xi = x;
    xi.tail<5>() *= alphad / x(5);
    try {
      out.push_back({alphad, P(xi)(5), "completed"});
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      const std::size_t a = what.find(": ") + 2;
      out.push_back({alphad, NAN, what.substr(a, what.find(':', a) - a)});
    }
  }
  return out;
}

std::string mapCsv(const std::vector<MapPoint>& m) {
  std::ostringstream o;
  o << "alphad_iSS,next_alphad_iSS,outcome\n";
  for (const MapPoint& p : m)
    o << formatDouble(p.alphad) << ',' << (std::isnan(p.next) ? "" : formatDouble(p.next)) << ','
      << p.outcome << '\n';
  return o.str();
}

std::string matrixCsv(const Eigen::MatrixXd& J) {
  std::ostringstream o;
  o << "alpha,delta1,delta2,delta3,delta4,alphad,delta1d,delta2d,delta3d,delta4d\n";
  for (Eigen::Index r = 0; r < J.rows(); ++r)
    for (Eigen::Index c = 0; c < J.cols(); ++c)
      o << formatDouble(J(r, c)) << (c + 1 < J.cols() ? ',' : '\n');
  return o.str();
}

}  // namespace

void registerStabilityCommand(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<StabilityArgs>();
  CLI::App* cmd = app.add_subcommand(
      "stability",
      "Poincare analysis of the closed-loop gait (gaitopt simulate's controller): fixed point, "
      "Jacobian on all DOF by central differences, eigenvalues, power iteration (4.61), and the "
      "1-D map of alphad at SS start. Writes OUT/stability.json, jacobian.csv, "
      "zero_dynamics_map.csv. Exit 3 if the cycle is unstable or not a fixed point.");
  cmd->add_option("--gait", a->gait, "Gait YAML file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", a->out, "Output directory")->required();
  cmd->add_option("--fd-step", a->step, "Finite-difference step on every state component")
      ->capture_default_str()
      ->check(CLI::Range(1e-9, 1e-1));
  cmd->add_option("--bandwidth", a->bandwidth, "Output bandwidth omega [rad/s]")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1000.0));
  cmd->add_option("--map-range", a->range, "Relative alphad range of the 1-D map (+-)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.95));
  cmd->add_option("--map-points", a->points, "Points of the 1-D map")
      ->capture_default_str()
      ->check(CLI::Range(2, 10001));
  cmd->callback([a, &exit_code]() {
    const GaitFile gait = loadGaitFile(a->gait);
    requireDirectoryOrAbsent(a->out);
    const GaitEvaluator ev(gait.robot, gait.options, gait.model_options);
    const GaitEvaluation<double> e = ev.evaluate(gait.parameters);
    if (!e.defined() || !e.motion_computed) {
      std::cerr << "gaitopt: error: " << a->gait << ": the step is undefined\n";
      exit_code = kExitUndefined;
      return;
    }
    const Model model = buildModel(gait.robot, gait.model_options);
    WalkRequest req;
    req.bandwidth = a->bandwidth;
    req.friction_coefficient = gait.options.friction_coefficient;
    req.tolerances = {1e-12, 1e-14};  // the map's noise must stay far below the FD step
    const StepMap P = walkingStepMap(e, model, model, req);
    const Eigen::VectorXd x = walkingCycleState(e.motion);
    const PoincareLinearisation L = linearisePoincare(P, x, Eigen::VectorXd::Constant(10, a->step));
    Eigen::VectorXd power_vector;
    const double power =
        powerIteration(P, x, Eigen::VectorXd::Constant(10, a->step), 6, power_vector);
    const std::vector<MapPoint> map = zeroDynamicsMap(P, x, a->range, a->points);

    JsonWriter w;
    w.beginObject();
    w.key("gait").value(a->gait);
    w.key("section").value("single-support start (after lift-off), x = (q, qd)");
    w.key("fixed_point").value(x);
    w.key("fixed_point_residual").value(L.fixed_point_residual);
    w.key("fd_step").value(a->step);
    w.key("bandwidth").value(a->bandwidth);
    w.key("eigenvalues_real").value(Eigen::VectorXd(L.eigenvalues.real()));
    w.key("eigenvalues_imag").value(Eigen::VectorXd(L.eigenvalues.imag()));
    w.key("dominant_modulus").value(std::abs(L.eigenvalues(0)));
    w.key("dominant_eigenvector_real").value(Eigen::VectorXd(L.dominant_vector.real()));
    w.key("power_iteration").beginObject();
    w.key("estimate").value(power);
    w.key("vector").value(power_vector);
    w.key("iterations").value(6);
    w.endObject();
    w.key("stable").value(std::abs(L.eigenvalues(0)) < 1.0);
    w.endObject();
    const fs::path dir(a->out);
    fs::create_directories(dir);
    writeFileAtomically((dir / "stability.json").string(), w.str() + "\n");
    writeFileAtomically((dir / "jacobian.csv").string(), matrixCsv(L.jacobian));
    writeFileAtomically((dir / "zero_dynamics_map.csv").string(), mapCsv(map));
    const bool stable = std::abs(L.eigenvalues(0)) < 1.0 && L.fixed_point_residual < 1e-6;
    std::cout << "stability: dominant |eigenvalue| " << shortNumber(std::abs(L.eigenvalues(0)))
              << ", power iteration " << shortNumber(power) << ", fixed-point residual "
              << shortNumber(L.fixed_point_residual) << (stable ? ", stable" : ", NOT stable")
              << " -> " << a->out << "\n";
    exit_code = stable ? 0 : kExitUndefined;
  });
}

}  // namespace gaitopt::cli
