#include "gaitopt/io/stability_report.hpp"

#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {

namespace {

// An empty CSV field for NaN (no value).
std::optional<double> csvNumber(double v) {
  return std::isnan(v) ? std::nullopt : std::optional<double>(v);
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

void writeMargins(JsonWriter& w, const StabilityMargins& m) {
  w.key("margins").beginObject();
  w.key("recovery_steps").value(m.request.steps);
  w.key("tolerance").value(m.request.tolerance);
  w.key("touchdown").value("foot height, impact model " + m.impact_model +
                           ", SS at once when the impact lifts the rear foot");
  writeMargin(w, "push_forward", m.push_forward, "m/s");
  writeMargin(w, "push_backward", m.push_backward, "m/s");
  writeMargin(w, "trunk_payload", m.trunk_payload, "kg");
  w.key("slope").beginObject();
  writeMargin(w, "up", m.slope_up, "rad");
  writeMargin(w, "down", m.slope_down, "rad");
  w.endObject();
  w.endObject();
}

}  // namespace

std::string stabilityJson(const StabilityStudy& s, const StabilityRequest& request,
                          const std::string& gait) {
  const PoincareLinearisation& L = s.linearisation;
  JsonWriter w;
  w.beginObject();
  w.key("gait").value(gait);
  w.key("section").value("single-support start (after lift-off), x = (q, qd)");
  w.key("fixed_point").value(s.fixed_point);
  w.key("fixed_point_residual").value(L.fixed_point_residual);
  w.key("jacobian_method").value(toString(s.jacobian_method));
  if (!s.jacobian_fallback.empty()) w.key("jacobian_fallback").value(s.jacobian_fallback);
  w.key("fd_step").value(request.fd_step);
  w.key("bandwidth").value(request.bandwidth);
  w.key("ds_control").value(toString(request.ds_control));
  w.key("eigenvalues_real").value(Eigen::VectorXd(L.eigenvalues.real()));
  w.key("eigenvalues_imag").value(Eigen::VectorXd(L.eigenvalues.imag()));
  w.key("dominant_modulus").value(s.dominant_modulus);
  w.key("dominant_eigenvector_real").value(Eigen::VectorXd(L.dominant_vector.real()));
  w.key("power_iteration").beginObject();
  w.key("estimate").value(s.power_estimate);
  w.key("vector").value(s.power_vector);
  w.key("iterations").value(request.power_iterations);
  w.endObject();
  w.key("stable").value(s.stable);
  w.key("torque_limits_in_analysis").value(false);
  w.key("saturated_samples_on_cycle").value(s.saturated_samples_on_cycle);
  writeZeroDynamics(w, s.zero_dynamics, s.zero_dynamics_max_steps);
  if (s.has_double_support)
    writeDsZone(w, s.ds_zone, s.ds_limits);
  else
    w.key("ds_time_optimal").null();  // no double support
  writeMargins(w, s.margins);
  w.endObject();
  return w.str() + "\n";
}

std::string jacobianCsv(const Eigen::MatrixXd& J) {
  std::ostringstream o;
  o << csvHeader({"alpha", "delta1", "delta2", "delta3", "delta4", "alphad", "delta1d", "delta2d",
                  "delta3d", "delta4d"});
  for (Eigen::Index r = 0; r < J.rows(); ++r) o << CsvRow().numbers(J.row(r)).line();
  return o.str();
}

std::string zeroDynamicsMapCsv(const ZeroDynamicsStudy& z) {
  std::ostringstream o;
  o << csvHeader({"alphad_iSS", "alphad_iDS", "next_alphad_iSS", "next_alphad_iDS",
                  "steps_to_cycle", "outcome"});
  for (const ZeroDynamicsPoint& p : z.points) {
    CsvRow row;
    row.number(p.alphad_iSS).number(csvNumber(p.alphad_iDS));
    row.number(csvNumber(p.next_alphad_iSS)).number(csvNumber(p.next_alphad_iDS));
    o << row.integer(p.steps_to_cycle).text(p.outcome).line();
  }
  return o.str();
}

std::string dsBoundsCsv(const DsZoneStudy& z) {
  std::ostringstream o;
  o << csvHeader({"alphad_fDS", "alphad_iDS_braking", "alphad_iDS_speeding_up", "a", "braking_end",
                  "speeding_up_end", "cycle_exists", "cycle_stable"});
  for (const DsZoneRow& r : z.rows) {
    CsvRow row;
    row.number(r.alphad_fDS).number(csvNumber(r.fastest_iDS)).number(csvNumber(r.slowest_iDS));
    row.number(csvNumber(r.a)).text(r.braking_end).text(r.speeding_up_end);
    o << row.integer(r.cycle_exists).integer(r.cycle_stable).line();
  }
  return o.str();
}

void writeStabilityReport(const std::string& dir, const StabilityStudy& s,
                          const StabilityRequest& request, const std::string& gait) {
  const std::filesystem::path d(dir);
  writeNewFile((d / "stability.json").string(), stabilityJson(s, request, gait));
  writeNewFile((d / "jacobian.csv").string(), jacobianCsv(s.linearisation.jacobian));
  writeNewFile((d / "zero_dynamics_map.csv").string(), zeroDynamicsMapCsv(s.zero_dynamics));
  if (s.has_double_support) writeNewFile((d / "ds_bounds.csv").string(), dsBoundsCsv(s.ds_zone));
}

}  // namespace gaitopt
