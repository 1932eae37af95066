// `gaitopt simulate`: closed-loop hybrid walking of a gait in gaitopt's own model.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include "cli_common.hpp"
#include "commands.hpp"
#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/gait/constraints/contact.hpp"
#include "gaitopt/io/atomic_file.hpp"
#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "gaitopt/model/chain_kinematics.hpp"
#include "gaitopt/sim/hybrid_walk.hpp"
#include "gaitopt/sim/impact_touchdown.hpp"

namespace gaitopt::cli {
namespace {

namespace fs = std::filesystem;

struct SimulateArgs {
  std::string gait, out, plant, impact = "auto", ds_control = "cubic";
  int steps = 20;
  double bandwidth = 40.0, sample_rate = 200.0, ground_mu = -1.0;
  bool no_torque_limits = false;
  std::vector<std::string> perturb;
};

// KIND=VALUE: alphad [rad/s] or alpha, delta1..delta4 [rad], added at the first SS start.
void applyPerturbation(const std::string& text, WalkRequest& req) {
  const std::size_t eq = text.find('=');
  static const std::map<std::string, int> coordinate{
      {"alpha", 0}, {"delta1", 1}, {"delta2", 2}, {"delta3", 3}, {"delta4", 4}};
  double v = 0.0;
  try {
    std::size_t used = 0;
    v = std::stod(text.substr(eq == std::string::npos ? text.size() : eq + 1), &used);
    if (eq + 1 + used != text.size()) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw CLI::ValidationError("--perturb", "expected KIND=VALUE, got '" + text + "'");
  }
  const std::string kind = text.substr(0, eq);
  if (kind == "alphad") {
    req.dalphad0 += v;
  } else if (kind == "slope") {
    if (std::abs(req.ground_slope + v) >= 0.5)
      throw CLI::ValidationError("--perturb", "slope must be within (-0.5, 0.5) rad, got '" +
                                                  text + "'");
    req.ground_slope += v;
  } else if (coordinate.count(kind)) {
    req.dq0(coordinate.at(kind)) += v;
  } else {
    throw CLI::ValidationError("--perturb", "unknown KIND '" + kind +
                                                "' (alphad, slope, alpha, delta1, delta2, delta3, delta4)");
  }
}

// The samples as export rows (world frame, physical joints, torque parts on the plant).
std::vector<ExportRow> exportRows(const Model& plant, const WalkResult& r) {
  std::vector<ExportRow> rows;
  double foot1_x = 0.0, next_foot1_x = 0.0;
  for (const WalkSample& s : r.samples) {
    const ChainState<double> st = chainState(plant, s.q, s.qd);
    const Vec2 foot2 = chainPoint(plant.pinned.foot2, st);
    if (s.single_support) next_foot1_x = foot1_x + foot2(0);  // where the swing foot lands
    if (!s.single_support && !rows.empty() && rows.back().phase == Phase::SingleSupport)
      foot1_x = next_foot1_x;
    const Leg stance = (s.step % 2 == 0) == s.single_support ? Leg::Left : Leg::Right;
    // exportRow reads the motion columns only; the drawing aids keep their defaults.
    TrajectoryRow tr =
        motionRow(s.t, s.single_support ? Phase::SingleSupport : Phase::DoubleSupport, s);
    tr.foot2 = foot2;
    tr.com = chainPoint(plant.pinned.b, st) / plant.total_mass;
    rows.push_back(exportRow(plant, tr, s.step, stance, foot1_x, s.t));
  }
  return rows;
}

std::string trackingCsv(const WalkResult& r, double mu) {
  std::ostringstream o;
  o << "t,step,phase,error1,error2,error3,error4,R1z,R2z,cone_margin1,cone_margin2\n";
  for (const WalkSample& s : r.samples) {
    o << formatDouble(s.t) << ',' << s.step << ',' << (s.single_support ? "SS" : "DS");
    for (int j = 0; j < 4; ++j) o << ',' << formatDouble(s.output_error(j));
    o << ',' << formatDouble(s.R1(1)) << ',' << formatDouble(s.R2(1)) << ','
      << formatDouble(-frictionConeExcess(s.R1, mu)) << ','
      << formatDouble(s.single_support ? 0.0 : -frictionConeExcess(s.R2, mu)) << '\n';
  }
  return o.str();
}

std::string stepsCsv(const WalkResult& r) {
  std::ostringstream o;
  o << "step,t_start,t_touchdown,t_liftoff,alphad_start,max_output_error,"
       "touchdown_event_residual,touchdown_foot_speed,energy_start,energy_touchdown,motor_work,"
       "friction_loss,min_normal_force,impact_behaviour,impact_energy_loss,impulse1_x,impulse1_z,"
       "impulse2_x,impulse2_z,energy_end,step_motor_work,step_friction_loss,energy_balance_error,"
       "saturated_samples,first_saturation_time\n";
  for (const WalkStep& s : r.steps)
    o << s.step << ',' << formatDouble(s.t_start) << ',' << formatDouble(s.t_touchdown) << ','
      << formatDouble(s.t_liftoff) << ',' << formatDouble(s.alphad_start) << ','
      << formatDouble(s.max_output_error) << ',' << formatDouble(s.touchdown_event_residual)
      << ',' << formatDouble(s.touchdown_foot_speed) << ',' << formatDouble(s.energy_start)
      << ',' << formatDouble(s.energy_touchdown) << ',' << formatDouble(s.motor_work) << ','
      << formatDouble(s.friction_loss) << ',' << formatDouble(s.min_normal_force) << ','
      << s.impact_behaviour << ',' << formatDouble(s.impact_energy_loss) << ','
      << formatDouble(s.impulse1(0)) << ',' << formatDouble(s.impulse1(1)) << ','
      << formatDouble(s.impulse2(0)) << ',' << formatDouble(s.impulse2(1)) << ','
      << formatDouble(s.energy_end) << ',' << formatDouble(s.step_motor_work) << ','
      << formatDouble(s.step_friction_loss) << ',' << formatDouble(stepEnergyBalanceError(s))
      << ',' << s.saturated_samples << ',' << formatDouble(s.first_saturation_time) << '\n';
  return o.str();
}

// Converged to a cycle: the last step started on the cycle's α̇ (to 1e-6) and repeated the
// previous step's largest output error (to 1e-6 rad).
bool converged(const WalkResult& r, double alphadot_iSS) {
  const std::size_t n = r.steps.size();
  if (r.outcome != WalkOutcome::Completed || n < 2) return false;
  return std::abs(r.steps[n - 1].alphad_start - alphadot_iSS) < 1e-6 &&
         std::abs(r.steps[n - 1].max_output_error - r.steps[n - 2].max_output_error) < 1e-6;
}

// Tracks the reference: converged with the outputs on the virtual constraints (to 1e-6 rad).
bool tracksReference(const WalkResult& r, double alphadot_iSS) {
  return converged(r, alphadot_iSS) && r.steps.back().max_output_error < 1e-6;
}

std::string summaryJson(const WalkResult& r, const SimulateArgs& a, const WalkRequest& req,
                        const GaitOptions& options, double alphadot_iSS) {
  JsonWriter w;
  w.beginObject();
  w.key("outcome").value(outcomeName(r.outcome));
  w.key("message").value(r.message);
  w.key("converged_to_cycle").value(converged(r, alphadot_iSS));
  w.key("tracks_reference").value(tracksReference(r, alphadot_iSS));
  w.key("steps_requested").value(a.steps);
  w.key("steps_completed")
      .value(static_cast<int>(r.steps.size()) - (r.outcome == WalkOutcome::Completed ? 0 : 1));
  w.key("gait").value(a.gait);
  w.key("plant").value(a.plant.empty() ? std::string("gait robot") : a.plant);
  w.key("bandwidth").value(req.bandwidth);
  w.key("perturbation").beginObject();
  w.key("alphad").value(req.dalphad0);
  w.key("dq").value(req.dq0);
  w.key("slope").value(req.ground_slope);
  w.endObject();
  w.key("impact_model").value(resolvedImpactModel(options, a.impact));
  w.key("ds_control").value(toString(req.ds_control));
  w.key("torque_limits").value(req.torque_limits);
  w.key("ground_friction_coefficient").value(req.plant_friction_coefficient);
  int saturated = 0;
  for (const WalkStep& s : r.steps) saturated += s.saturated_samples;
  w.key("saturated_samples").value(saturated);
  w.key("cycle_alphad_start").value(alphadot_iSS);
  w.key("last_alphad_start").value(r.steps.empty() ? 0.0 : r.steps.back().alphad_start);
  w.endObject();
  return w.str() + "\n";
}

}  // namespace

void registerSimulateCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Closed-loop hybrid walking of a gait in gaitopt's model (CVODE, events by root finding, "
      "thesis 4.3.1 controller with alpha replacing time). Writes OUT/summary.json, "
      "steps.csv, trajectory.csv, tracking.csv. Exit 0: every step walked; 3: it did not.");
  cmd->add_option("--gait", args->gait, "Gait YAML file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "Output directory (created if missing)")->required();
  cmd->add_option("--steps", args->steps, "Number of steps")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--perturb", args->perturb,
                  "KIND=VALUE added at the first SS start: alphad [rad/s] (on the virtual "
                  "constraints) or alpha, delta1..delta4 [rad]; slope [rad]: the ground ahead "
                  "of the first stance foot inclined, + uphill; repeatable");
  cmd->add_option("--plant", args->plant,
                  "Robot file of the simulated robot (default: the gait's robot)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--bandwidth", args->bandwidth, "Output bandwidth omega [rad/s]")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1000.0));
  cmd->add_option("--sample-rate", args->sample_rate, "trajectory rows [Hz]")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1e5));
  cmd->add_option("--impact", args->impact,
                  "Touchdown model: auto (double_support for a zero-velocity landing with DS, "
                  "none without DS, algebraic for an impact landing), none (impulse-free only), "
                  "double_support (plastic impact, both feet held), algebraic, differential")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "none", "double_support", "algebraic", "differential"}));
  addDsControlOption(cmd, args->ds_control);
  cmd->add_option("--ground-mu", args->ground_mu,
                  "Friction coefficient of the plant's ground (slip checks, impacts); default: "
                  "the gait's friction_coefficient")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_flag("--no-torque-limits", args->no_torque_limits,
                "Do not project the inputs on the torque envelope and contact constraints");
  cmd->callback([args, &exit_code]() {
    const GaitFile gait = loadGaitFile(args->gait);
    WalkRequest req;
    for (const std::string& p : args->perturb) applyPerturbation(p, req);
    req.steps = args->steps;
    req.bandwidth = args->bandwidth;
    req.sample_rate = args->sample_rate;
    configureForGait(gait.options, req);
    if (args->ground_mu >= 0.0) req.plant_friction_coefficient = args->ground_mu;
    req.torque_limits = !args->no_torque_limits;
    req.ds_control = dsAlphaControlOf(args->ds_control);
    const Model controller = buildModel(gait.robot, gait.model_options);
    const Model plant =
        args->plant.empty() ? controller : buildModel(loadRobot(args->plant), gait.model_options);
    requireDirectoryOrAbsent(args->out);
    const GaitEvaluator evaluator(gait.robot, gait.options, gait.model_options);
    const GaitEvaluation<double> e = evaluator.evaluate(gait.parameters);
    if (!e.defined() || !e.motion_computed) {
      std::cerr << "gaitopt: error: " << args->gait << ": the step is undefined\n";
      exit_code = kExitUndefined;
      return;
    }
    const WalkResult r = simulateWalk(
        e, controller, plant, req,
        gaitTouchdown(gait.options, args->impact, req.plant_friction_coefficient));
    ExportRequest meta_req;
    meta_req.steps = args->steps;
    meta_req.rate = args->sample_rate;
    const fs::path dir(args->out);
    fs::create_directories(dir);
    writeFileAtomically((dir / "summary.json").string(),
                        summaryJson(r, *args, req, gait.options, e.motion.alphadot_iSS));
    writeFileAtomically((dir / "steps.csv").string(), stepsCsv(r));
    writeFileAtomically((dir / "trajectory.csv").string(),
                        exportCsv(exportMetadata(gait, e, meta_req), exportRows(plant, r)));
    writeFileAtomically((dir / "tracking.csv").string(),
                        trackingCsv(r, gait.options.friction_coefficient));
    std::cout << "simulate: " << outcomeName(r.outcome)
              << (r.message.empty() ? "" : " (" + r.message + ")") << ", "
              << r.steps.size() << " steps, converged "
              << (converged(r, e.motion.alphadot_iSS) ? "yes" : "no") << ", tracks reference "
              << (tracksReference(r, e.motion.alphadot_iSS) ? "yes" : "no") << " -> " << args->out
              << "\n";
    exit_code = r.outcome == WalkOutcome::Completed ? 0 : kExitUndefined;
  });
}

}  // namespace gaitopt::cli
