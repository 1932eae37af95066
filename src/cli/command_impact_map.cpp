// `gaitopt impact-map`: behaviour of the impact over the direction θ of the arriving foot
// velocity and the friction coefficient μ → DIR/map.csv (and DIR/intervals.csv, algebraic).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "cli_common.hpp"
#include "data_files.hpp"
#include "commands.hpp"
#include "gaitopt/impact/impact_map.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "impact_input.hpp"

namespace gaitopt::cli {
namespace {

struct ImpactMapArgs {
  std::string robot;  // empty: the default robot (data_files.hpp)
  std::string q;
  std::string mu_range = "0:1.5:31", theta_range = "-180:0:181";
  std::string model = "algebraic";
  std::string out;
};

constexpr double kDeg = M_PI / 180.0;
// Grid points (μ samples × θ samples) of one map: 10^6 keep a run within a few seconds (the
// differential model about ten times more) and a quarter of a GB (docs/reliability.md).
constexpr long long kMaxMapPoints = 1000000;

std::string labels(const std::vector<ImpactBehaviour>& behaviours) {
  if (behaviours.empty()) return "none";
  std::string s;
  for (ImpactBehaviour b : behaviours) s += (s.empty() ? "" : "|") + behaviourLabel(b);
  return s;
}

std::string mapCsv(const std::vector<ImpactMapRow>& rows) {
  std::ostringstream out;
  out << csvHeader({"theta_deg", "mu", "behaviour", "n_solutions", "status"});
  for (const ImpactMapRow& r : rows) {
    CsvRow row;
    row.number(r.theta / kDeg, "%.10g").number(r.mu, "%.10g").text(labels(r.behaviours));
    out << row.integer(r.behaviours.size()).text(toString(r.status)).line();
  }
  return out.str();
}

std::string intervalsCsv(const Model& model, const Vec5& q, const ImpactMapRequest& req) {
  std::ostringstream out;
  out << csvHeader({"mu", "behaviour", "theta_begin_deg", "theta_end_deg"});
  for (int i = 0; i < req.mu_count; ++i) {
    const double mu = req.mu_count <= 1 ? req.mu_min
                                        : req.mu_min + (req.mu_max - req.mu_min) * i /
                                                           static_cast<double>(req.mu_count - 1);
    for (const ThetaInterval& iv :
         algebraicThetaIntervals(model, q, mu, req.theta_min, req.theta_max)) {
      CsvRow row;
      row.number(mu, "%.10g").text(behaviourLabel(iv.behaviour));
      out << row.number(iv.begin / kDeg, "%.12g").number(iv.end / kDeg, "%.12g").line();
    }
  }
  return out.str();
}

int runImpactMap(const ImpactMapArgs& args) {
  const std::string robot = robotOrDefault(args.robot, "impact-map");
  const Model model = buildModel(loadRobot(robot));
  const std::vector<double> qv = parseNumberList("--q", args.q, 5);
  const SampleRange mu = parseSampleRange("--mu-range", args.mu_range);
  const SampleRange theta = parseSampleRange("--theta-range", args.theta_range);
  requireFriction("--mu-range", std::min(mu.a, mu.b));
  if (static_cast<long long>(mu.n) * theta.n > kMaxMapPoints)
    throw BadImpactInput("--mu-range, --theta-range: " + std::to_string(mu.n) + " x " +
                         std::to_string(theta.n) + " points, more than the limit of " +
                         std::to_string(kMaxMapPoints));
  const Vec5 q = foot2OnGround(model, Vec5(Eigen::Map<const Vec5>(qv.data())), "impact-map");
  OutputTransaction output({{"--robot", robot}});
  const std::string dir =
      output.directory("--out", args.out, ourFiles({"map.csv", "intervals.csv"}));
  ImpactMapRequest req;
  req.model = parseImpactModel(args.model);
  req.mu_min = mu.a;
  req.mu_max = mu.b;
  req.mu_count = mu.n;
  req.theta_min = theta.a * kDeg;
  req.theta_max = theta.b * kDeg;
  req.theta_count = theta.n;
  const std::string map = mapCsv(impactMap(model, q, req));
  writeNewFile(dir + "/map.csv", map);
  if (req.model == ImpactModelKind::Algebraic)
    writeNewFile(dir + "/intervals.csv", intervalsCsv(model, q, req));
  output.commit();
  return 0;
}

}  // namespace

void registerImpactMapCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ImpactMapArgs>();
  CLI::App* cmd = app.add_subcommand(
      "impact-map",
      "Impact behaviour over the arriving-velocity direction theta (V2- = (cos, sin)) and the "
      "friction coefficient: writes DIR/map.csv (and DIR/intervals.csv with the exact "
      "theta-intervals for the algebraic model).");
  addRobotOption(cmd, args->robot);
  cmd->add_option("--q", args->q, "Double-support configuration, 5 values [rad]")->required();
  cmd->add_option("--mu-range", args->mu_range, "Friction samples a:b:n")->capture_default_str();
  cmd->add_option("--theta-range", args->theta_range, "Direction samples a:b:n [deg]")
      ->capture_default_str();
  cmd->add_option("--model", args->model, "Impact model: algebraic | differential")
      ->capture_default_str()
      ->check(CLI::IsMember({"algebraic", "differential"}));
  cmd->add_option("--out", args->out, "Output directory (created if missing)")->required();
  cmd->callback([args, &exit_code]() {
    exit_code = exitCodeOf("impact-map", [&args]() { return runImpactMap(*args); });
  });
}

}  // namespace gaitopt::cli
