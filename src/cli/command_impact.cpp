// `gaitopt impact`: the rigid impact of foot 2 at one configuration and pre-impact velocity,
// as one JSON document on standard output.
#include <iostream>
#include <memory>

#include "cli_common.hpp"
#include "data_files.hpp"
#include "commands.hpp"
#include "gaitopt/impact/solve_impact.hpp"
#include "gaitopt/io/impact_report.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "impact_input.hpp"

namespace gaitopt::cli {
namespace {

struct ImpactArgs {
  std::string robot;  // empty: the default robot (data_files.hpp)
  std::string q, qd;
  std::string model = "algebraic";
  double mu = 0.0;
};

Vec5 toVec5(const std::vector<double>& v) { return Vec5(Eigen::Map<const Vec5>(v.data())); }

int runImpact(const ImpactArgs& args) {
  const Model model = buildModel(loadRobot(robotOrDefault(args.robot, "impact")));
  const Vec5 q_given = toVec5(parseNumberList("--q", args.q, 5));
  const Vec5 qd = toVec5(parseNumberList("--qd", args.qd, 5));
  const Vec5 q = foot2OnGround(model, q_given, "impact");
  const double v2z = foot2VerticalVelocity(model, q, qd);
  if (!(v2z < 0.0))
    throw BadImpactInput("--qd: foot 2 vertical velocity V2z = " + shortNumber(v2z) +
                         " m/s; foot 2 must arrive with V2z < 0");
  ImpactOptions options;
  options.mu = args.mu;
  const ImpactResult r =
      solveImpactFromPinned(model, q, qd, parseImpactModel(args.model), options);
  JsonWriter w;
  w.beginObject();
  w.key("q").value(q);  // the configuration used: --q with foot 2 projected onto the ground
  writeImpactResultFields(w, r);
  w.endObject();
  std::cout << w.str() << "\n";
  return r.solutions.empty() ? kExitUndefined : 0;
}

}  // namespace

void registerImpactCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ImpactArgs>();
  CLI::App* cmd = app.add_subcommand(
      "impact",
      "Rigid impact of foot 2 (zero restitution, Coulomb friction) at a double-support "
      "configuration: every consistent solution as JSON. Exit 0: at least one solution; "
      "3: inconsistent (none); 2: bad input.");
  addRobotOption(cmd, args->robot);
  cmd->add_option("--q", args->q,
                  "Pinned configuration alpha,delta1,delta2,delta3,delta4 [rad], foot 1 at the "
                  "origin, foot 2 on the ground")
      ->required();
  cmd->add_option("--qd", args->qd,
                  "Pre-impact pinned velocities [rad/s], 5 values (foot 1 at rest); foot 2 must "
                  "arrive with V2z < 0")
      ->required();
  cmd->add_option("--model", args->model, "Impact model: algebraic | differential")
      ->capture_default_str()
      ->check(CLI::IsMember({"algebraic", "differential"}));
  cmd->add_option("--mu", args->mu, "Coulomb friction coefficient (>= 0)")
      ->required()
      ->check(numberWithin(0.0, 100.0));
  cmd->callback([args, &exit_code]() {
    exit_code = exitCodeOf("impact", [&args]() { return runImpact(*args); });
  });
}

}  // namespace gaitopt::cli
