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
#include "gaitopt/sim/ds_convergence_zone.hpp"
#include "gaitopt/sim/impact_touchdown.hpp"
#include "gaitopt/sim/poincare_sensitivity.hpp"
#include "gaitopt/sim/stability_margins.hpp"
#include "gaitopt/sim/zero_dynamics_map.hpp"

namespace gaitopt::cli {
namespace {

namespace fs = std::filesystem;

struct StabilityArgs {
  std::string gait, out, jacobian = "sensitivity", ds_control = "cubic";
  double step = 1e-4, bandwidth = 40.0, range = 0.05, ds_range = 0.5;
  int points = 51, ds_points = 41;
  int margin_steps = 5;
};

std::string mapCsv(const ZeroDynamicsStudy& z) {
  std::ostringstream o;
  o << "alphad_iSS,alphad_iDS,next_alphad_iSS,next_alphad_iDS,steps_to_cycle,outcome\n";
  auto num = [](double v) { return std::isnan(v) ? std::string() : formatDouble(v); };
  for (const ZeroDynamicsPoint& p : z.points)
    o << formatDouble(p.alphad_iSS) << ',' << num(p.alphad_iDS) << ',' << num(p.next_alphad_iSS)
      << ',' << num(p.next_alphad_iDS) << ',' << p.steps_to_cycle << ',' << p.outcome << '\n';
  return o.str();
}

void writeZeroDynamics(JsonWriter& w, const ZeroDynamicsStudy& z, int max_steps) {
  w.key("zero_dynamics").beginObject();
  w.key("section").value("SS start on the virtual constraints, alphad_iSS");
  w.key("fixed_point").value(z.fixed_point);
  w.key("fixed_point_residual").value(z.fixed_point_residual);
  w.key("slope").value(z.slope);
  w.key("stable").value(z.stable);
  w.key("one_step_region").value(Eigen::Vector2d(z.one_step_low, z.one_step_high));
  w.key("global_region").value(Eigen::Vector2d(z.global_low, z.global_high));
  w.key("global_max_steps").value(max_steps);
  w.key("resolution").value(z.resolution);
  w.endObject();
}

// Fig. 4.5: per α̇_fDS the zone's ends at α_iDS and a (4.28).
std::string dsBoundsCsv(const DsZoneStudy& z) {
  std::ostringstream o;
  o << "alphad_fDS,alphad_iDS_braking,alphad_iDS_speeding_up,a,braking_end,speeding_up_end,"
       "cycle_exists,cycle_stable\n";
  auto num = [](double v) { return std::isnan(v) ? std::string() : formatDouble(v); };
  for (const DsZoneRow& r : z.rows)
    o << formatDouble(r.alphad_fDS) << ',' << num(r.fastest_iDS) << ',' << num(r.slowest_iDS)
      << ',' << num(r.a) << ',' << r.braking_end << ',' << r.speeding_up_end << ','
      << r.cycle_exists << ',' << r.cycle_stable << '\n';
  return o.str();
}

void writeDsZone(JsonWriter& w, const DsZoneStudy& z, const DsLimits& l) {
  w.key("ds_time_optimal").beginObject();
  w.key("model").value("perfect tracking of delta1,2(alpha) in DS (H1-H3), LPs (4.14)");
  w.key("friction_coefficient").value(l.friction_coefficient);
  w.key("min_normal_force").value(l.min_normal_force);
  w.key("full_torque_envelope").value(l.full_torque_envelope);
  w.key("alpha_iDS").value(z.alpha_iDS);
  w.key("alpha_fDS").value(z.alpha_fDS);
  w.key("cycle_alphad_iDS").value(z.cycle_alphad_iDS);
  w.key("cycle_alphad_fDS").value(z.cycle_alphad_fDS);
  w.key("cycle_fastest_alphad_iDS").value(z.cycle.fastest_iDS);
  w.key("cycle_slowest_alphad_iDS").value(z.cycle.slowest_iDS);
  w.key("cycle_braking_end").value(z.cycle.braking_end);
  w.key("cycle_speeding_up_end").value(z.cycle.speeding_up_end);
  w.key("cycle_in_zone").value(z.cycle_in_zone);
  w.key("cycle_strictly_inside").value(z.cycle_strictly_inside);
  w.key("one_step_region_alphad_iDS")
      .value(Eigen::Vector2d(z.cycle.fastest_iDS, z.cycle.slowest_iDS));
  w.key("cycle_braking_margin").value(z.cycle_braking_margin);
  w.key("cycle_speeding_up_margin").value(z.cycle_speeding_up_margin);
  w.key("from_rest_end").value(z.from_rest.end);
  w.key("from_rest_end_alphad").value(z.from_rest.end_alphad);
  w.key("existence_region_alphad_fDS").value(Eigen::Vector2d(z.existence_low, z.existence_high));
  w.key("ss_upper_bound_checked").value(false);
  w.endObject();
}

void writeMargin(JsonWriter& w, const char* name, const Margin& m, const char* unit) {
  w.key(name).beginObject();
  w.key("value").value(m.value);
  w.key("resolution").value(m.resolution);
  w.key("unit").value(unit);
  w.key("bracket_reached").value(m.bracket_reached);
  w.key("limit").value(m.limit);
  w.endObject();
}

void writeMargins(JsonWriter& w, const GaitFile& gait, const GaitEvaluation<double>& e,
                  const Model& model, const WalkRequest& req, int steps) {
  MarginRequest mr;
  mr.steps = steps;
  // A perturbed step lands with non-zero velocity, located by foot height: the touchdown map of
  // simulate (a DS gait's plastic impact with both feet held, else the algebraic rigid impact),
  // except that an impact lifting the rear foot starts the next SS at once (DS skipped).
  const std::string impact = resolvedImpactModel(gait.options, "auto");
  const double mu = gait.options.friction_coefficient;
  const TouchdownMap td = impact == "double_support" ? doubleSupportTouchdown(mu, true)
                                                     : gaitTouchdown(gait.options, impact, mu);
  w.key("margins").beginObject();
  w.key("recovery_steps").value(mr.steps);
  w.key("tolerance").value(mr.tolerance);
  w.key("touchdown").value("foot height, impact model " + impact +
                           ", SS at once when the impact lifts the rear foot");
  writeMargin(w, "push_forward", largestPush(e, model, req, 1, mr, td), "m/s");
  writeMargin(w, "push_backward", largestPush(e, model, req, -1, mr, td), "m/s");
  writeMargin(w, "trunk_payload",
              largestPayload(e, gait.robot, gait.model_options, req, mr, td), "kg");
  w.key("slope").beginObject();
  writeMargin(w, "up", largestSlope(e, model, req, 1, mr, td), "rad");
  writeMargin(w, "down", largestSlope(e, model, req, -1, mr, td), "rad");
  w.endObject();
  w.endObject();
}

// Samples of one cycle step where the torque projection acts: 0 means the linearised field is
// the smooth unsaturated one.
int saturatedOnCycle(const GaitEvaluation<double>& e, const Model& model, const WalkRequest& base,
                     const Eigen::VectorXd& x, const TouchdownMap& td) {
  WalkRequest req = base;
  req.steps = 1;
  req.use_initial_state = true;
  req.q_init = x.head<5>();
  req.qd_init = x.tail<5>();
  const WalkResult r = simulateWalk(e, model, model, req, td);
  return r.steps.empty() ? 0 : r.steps.front().saturated_samples;
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
  cmd->add_option("--fd-step", a->step,
                  "Finite-difference step on every state component (--jacobian fd, power "
                  "iteration box)")
      ->capture_default_str()
      ->check(CLI::Range(1e-9, 1e-1));
  cmd->add_option("--bandwidth", a->bandwidth, "Output bandwidth omega [rad/s]")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 1000.0));
  cmd->add_option("--map-range", a->range, "Relative alphad range of the 1-D map (+-)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.95));
  cmd->add_option("--margin-steps", a->margin_steps,
                  "Steps walked after a push, on a slope or with a payload (margins)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  cmd->add_option("--map-points", a->points, "Points of the 1-D map")
      ->capture_default_str()
      ->check(CLI::Range(2, 10001));
  addDsControlOption(cmd, a->ds_control);
  cmd->add_option("--ds-range", a->ds_range,
                  "Relative alphad_fDS range of the DS convergence-zone study (Fig. 4.5, +-)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.95));
  cmd->add_option("--ds-points", a->ds_points, "Points of the DS convergence-zone study")
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
    req.ds_control = dsAlphaControlOf(a->ds_control);
    configureForGait(gait.options, req);
    // The map's noise must stay far below the FD step.
    req.tolerances.relative = 1e-12;
    req.tolerances.absolute = 1e-14;
    // The linearisation needs a smooth field: the unsaturated controller (the projection on
    // the torque limits is non-smooth); margins and the saturation count use the projection.
    WalkRequest analysis = req;
    analysis.torque_limits = false;
    // A zero-velocity landing's foot height is tangent to the ground at α_fSS (no transversal
    // crossing for the saltation matrix): the analysis locates its touchdown by α, impulse-free.
    const bool impact_landing = gait.options.parameterisation.landsWithImpact();
    analysis.touchdown_by_foot_height = impact_landing;
    analysis.hold_references_past_fss = false;
    const TouchdownMap td = gaitTouchdown(gait.options, impact_landing ? "auto" : "none",
                                          gait.options.friction_coefficient);
    const StepMap P = walkingStepMap(e, model, model, analysis, td);
    const Eigen::VectorXd x = walkingCycleState(e.motion);
    const PoincareLinearisation L =
        a->jacobian == "fd"
            ? linearisePoincare(P, x, Eigen::VectorXd::Constant(10, a->step))
            : linearisePoincareBySensitivity(e, model, model, analysis, x, td);
    Eigen::VectorXd power_vector;
    const double power =
        powerIteration(P, x, Eigen::VectorXd::Constant(10, a->step), 6, power_vector);
    ZeroDynamicsRequest zr;
    zr.range = a->range;
    zr.points = a->points;
    zr.touchdown = td;
    const ZeroDynamicsStudy zd = studyZeroDynamics(e, model, model, analysis, zr);
    const bool has_ds = gait.options.parameterisation.hasDoubleSupport();
    const DsLimits limits = dsLimitsOf(gait.options);
    std::vector<double> grid;
    for (int i = 0; has_ds && i < a->ds_points; ++i)
      grid.push_back(e.motion.ds_alpha(e.motion.T_DS).first *
                     (1.0 + a->ds_range * (2.0 * i / (a->ds_points - 1) - 1.0)));
    const DsZoneStudy dz = has_ds ? studyDsZone(model, e.motion, limits, grid) : DsZoneStudy{};

    JsonWriter w;
    w.beginObject();
    w.key("gait").value(a->gait);
    w.key("section").value("single-support start (after lift-off), x = (q, qd)");
    w.key("fixed_point").value(x);
    w.key("fixed_point_residual").value(L.fixed_point_residual);
    w.key("jacobian_method").value(a->jacobian);
    w.key("fd_step").value(a->step);
    w.key("bandwidth").value(a->bandwidth);
    w.key("ds_control").value(a->ds_control);
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
    w.key("torque_limits_in_analysis").value(false);
    w.key("saturated_samples_on_cycle").value(saturatedOnCycle(
        e, model, req, x, gaitTouchdown(gait.options, "auto", gait.options.friction_coefficient)));
    writeZeroDynamics(w, zd, zr.max_steps);
    if (has_ds)
      writeDsZone(w, dz, limits);
    else
      w.key("ds_time_optimal").null();  // no double support
    writeMargins(w, gait, e, model, req, a->margin_steps);
    w.endObject();
    const fs::path dir(a->out);
    fs::create_directories(dir);
    writeFileAtomically((dir / "stability.json").string(), w.str() + "\n");
    writeFileAtomically((dir / "jacobian.csv").string(), matrixCsv(L.jacobian));
    writeFileAtomically((dir / "zero_dynamics_map.csv").string(), mapCsv(zd));
    if (has_ds) writeFileAtomically((dir / "ds_bounds.csv").string(), dsBoundsCsv(dz));
    const bool stable = std::abs(L.eigenvalues(0)) < 1.0 && L.fixed_point_residual < 1e-6;
    std::cout << "stability: dominant |eigenvalue| " << shortNumber(std::abs(L.eigenvalues(0)))
              << ", power iteration " << shortNumber(power) << ", fixed-point residual "
              << shortNumber(L.fixed_point_residual) << (stable ? ", stable" : ", NOT stable")
              << " -> " << a->out << "\n";
    exit_code = stable ? 0 : kExitUndefined;
  });
}

}  // namespace gaitopt::cli
