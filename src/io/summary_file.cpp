#include "gaitopt/io/summary_file.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "gaitopt/gait/cost_of_transport.hpp"
#include "gaitopt/gait/constraint_summary.hpp"
#include "gaitopt/gait/feasibility.hpp"
#include "gaitopt/gait/impact_landing.hpp"

namespace gaitopt {

namespace {

void numberOrNull(JsonWriter& w, bool available, double v) {
  if (available && std::isfinite(v)) {
    w.value(v);
  } else {
    w.null();
  }
}

void vectorValue(JsonWriter& w, const Eigen::Ref<const Eigen::VectorXd>& v) {
  w.beginArray();
  for (Eigen::Index i = 0; i < v.size(); ++i) w.value(v(i));
  w.endArray();
}

// The touchdown impact at the step's pre-impact rate α̇_fSS; null members when the zero
// dynamics did not run.
void writeImpactSummary(JsonWriter& w, const GaitEvaluator& ev, const GaitEvaluation<double>& e) {
  const Landing landing = ev.options().parameterisation.landing;
  const ImpactBehaviour b = landingBehaviour(landing);
  w.key("impact").beginObject();
  w.key("model").value("algebraic");
  w.key("after_impact").value(afterImpactName(landing));
  w.key("behaviour").beginObject();
  w.key("foot1").value(toString(b.foot1));
  w.key("foot2").value(toString(b.foot2));
  w.endObject();
  const bool timing = zeroDynamicsComputed(ev, e);
  if (!timing) {
    w.key("status").null();
    w.endObject();
    return;
  }
  const LandingReport r = landingReport(e.motion.landing, landing, e.alphadot_fSS);
  const LandingSolutions all = landingSolutions(ev.model(), r, ev.options().friction_coefficient);
  w.key("status").value(all.status);
  w.key("n_solutions").value(all.count);
  w.key("required_behaviour_consistent").value(all.required_found);
  w.key("differential").beginObject();
  w.key("status").value(all.differential_status);
  w.key("n_solutions").value(all.differential_count);
  w.key("max_Xd_plus_difference").value(all.differential_difference);
  w.endObject();
  w.key("impulse_foot1");
  vectorValue(w, r.impulse1);
  w.key("impulse_foot2");
  vectorValue(w, r.impulse2);
  w.key("energy_loss").value(r.energy_loss);
  w.key("energy_loss_per_metre").value(r.energy_loss / e.step_length);
  w.key("alphadot_minus").value(r.alphadot_minus);
  w.key("alphadot_plus").value(r.alphadot_plus);
  w.key("rate_ratio").value(e.motion.landing.rate_ratio);
  w.key("V2_minus");
  vectorValue(w, r.v2_minus);
  w.key("Xd_minus");
  vectorValue(w, r.Xd_minus);
  w.key("Xd_plus");
  vectorValue(w, r.Xd_plus);
  w.endObject();
}

// The 10× finer check of the phase-wise constraints; null when the motion was not computed.
void writeBetweenNodes(JsonWriter& w, const GaitEvaluator& ev, const BetweenNodesCheck& b,
                       bool computed) {
  w.key("between_nodes");
  if (!computed || !b.computed || b.worst_group < 0) {
    w.null();
    return;
  }
  w.beginObject();
  w.key("ss_nodes").value(b.ss_nodes);
  w.key("ds_nodes").value(b.ds_nodes);
  w.key("worst_constraint").value(ev.layout()[b.worst_group].name);
  w.key("worst_value").value(b.worst_value);
  w.key("worst_scaled").value(b.worst_scaled);
  w.key("satisfied").value(b.worst_scaled <= kFeasibilityTolerance);
  w.endObject();
}

// Only for a step evaluated without dry friction on a robot that has some.
void writeRobotFriction(JsonWriter& w, const GaitEvaluator& ev, const RobotFrictionCheck& c) {
  if (!c.checked) return;
  w.key("robot_friction").beginObject();
  w.key("group").value(ev.layout()[c.worst_group].name);
  w.key("excess").value(c.excess);
  w.key("unit").value(ev.layout()[c.worst_group].unit);
  w.key("satisfied").value(c.met);
  w.key("message").value(robotFrictionMessage(ev.layout(), c));
  w.endObject();
}

}  // namespace

void writeGaitSummaryMembers(JsonWriter& w, const GaitEvaluator& ev, const GaitParameters& p,
                             const GaitEvaluation<double>& e) {
  const bool defined = e.defined();
  const bool criteria = e.motion_computed && defined;
  const bool timing = zeroDynamicsComputed(ev, e);
  const GaitOptions& o = ev.options();

  w.key("status").value(defined ? "ok" : "undefined");
  // The one verdict (gait/feasibility.hpp): node entries, between nodes and speed.
  const FeasibilityVerdict verdict = feasibilityVerdict(ev, p, e);
  w.key("feasible").value(verdict.feasible);
  w.key("failed_level");
  if (verdict.failed_level < 0) {
    w.null();
  } else {
    w.value(verdict.failed_level);
  }
  w.key("unmet_constraints").beginArray();
  for (const std::string& name : verdict.unmet_groups) w.value(name);
  w.endArray();
  w.key("feasibility_tolerance").value(kFeasibilityTolerance);
  writeRobotFriction(w, ev, verdict.robot_friction);
  writeBetweenNodes(w, ev, verdict.between_nodes, e.motion_computed);
  w.key("motion_computed").value(e.motion_computed);
  w.key("numerically_undefined").value(e.numerically_undefined);
  w.key("robot").value(ev.model().robot.name);

  w.key("criteria");
  if (criteria) {
    w.beginObject();
    w.key("C_Gamma").value(e.C_Gamma);
    w.key("C_E").value(e.C_E);
    w.key("W").value(e.W);
    w.key("C_frott").value(e.C_frott);
    w.key("cost_of_transport").value(costOfTransport(ev.model(), e.C_E));
    w.endObject();
  } else {
    w.null();
  }
  w.key("speed");
  numberOrNull(w, timing, e.speed);
  w.key("step_length").value(e.step_length);
  w.key("T_SS");
  numberOrNull(w, timing, e.T_SS);
  w.key("T_DS").value(e.T_DS);
  w.key("alphadot_fSS");
  numberOrNull(w, timing, e.alphadot_fSS);
  w.key("target_speed");
  numberOrNull(w, o.target_speed > 0.0, o.target_speed);
  w.key("speed_error");  // (3.50) as a residual: speed − target_speed
  numberOrNull(w, timing && o.target_speed > 0.0, e.speed - o.target_speed);

  w.key("parameters").beginObject();
  const std::vector<std::string> names = ev.options().parameterisation.names();
  for (int i = 0; i < static_cast<int>(names.size()); ++i) w.key(names[i]).value(p(i));
  w.endObject();

  w.key("constraints").beginArray();
  for (int id = 0; id < static_cast<int>(ev.layout().groups().size()); ++id) {
    const ConstraintGroup& g = ev.layout()[id];
    if (g.count == 0) continue;  // a group this gait family does not have
    const double tolerance = kFeasibilityTolerance * constraintGroupScale(id, ev.model());
    const ConstraintGroupSummary s = summarizeConstraintGroup(g, e, tolerance);
    const bool has_value = s.defined > 0 && std::isfinite(s.value);
    w.beginObject();
    w.key("name").value(g.name);
    w.key("level").value(g.level);
    w.key("equation").value(g.equation);
    w.key("unit").value(g.unit);
    w.key("value");
    numberOrNull(w, has_value, s.value);
    w.key("satisfied");
    if (has_value) {
      w.value(s.value <= tolerance);
    } else {
      w.null();
    }
    w.key("count").value(g.count);
    w.key("defined").value(s.defined);
    w.key("violated").value(s.violated);
    w.endObject();
  }
  w.endArray();
  w.key("max_violation").value(maxDefinedViolation(e));

  w.key("ds_switch_times").beginArray();
  if (criteria) {
    for (double t : e.ds_pieces.switch_times) w.value(t);
  }
  w.endArray();

  if (o.parameterisation.landsWithImpact()) writeImpactSummary(w, ev, e);

  w.key("options").beginObject();
  w.key("friction_coefficient").value(o.friction_coefficient);
  w.key("clearance_height").value(o.clearance_height);
  w.key("min_normal_force").value(o.min_normal_force);
  w.key("dry_friction").value(o.dry_friction);
  w.key("ds_distribution").value(o.ds_distribution == DsDistribution::Torque ? "torque" : "energy");
  w.key("sample_rate").value(o.sample_rate);
  w.key("ss_nodes").value(o.ss_nodes);
  w.key("ds_nodes").value(o.ds_nodes);
  w.key("criteria_refinement").value(o.criteria_refinement);
  w.key("f_min").value(o.f_min);
  w.key("alphadot_margin").value(o.alphadot_margin);
  w.key("ds_alphadot_max").value(o.ds_alphadot_max);
  w.key("angle_margin").value(o.angle_margin);
  w.key("reach_margin").value(o.reach_margin);
  w.key("kappa_min").value(o.kappa_min);
  w.key("joint_limit_margin").value(o.joint_limit_margin);
  w.key("full_torque_envelope").value(o.full_torque_envelope);
  w.key("target_speed").value(o.target_speed);
  if (o.parameterisation.landsWithImpact()) {
    w.key("landing").value("impact");
    w.key("after_impact").value(afterImpactName(o.parameterisation.landing));
    w.key("touchdown_speed_min").value(o.touchdown_speed_min);
  }
  const ModelOptions& mo = ev.model().options;
  w.key("rotor").value(mo.rotor == RotorModel::Exact ? "exact" : "high_gear");
  w.key("friction_smoothing").value(mo.friction_smoothing);
  w.endObject();

  static constexpr std::pair<const char*, const char*> kUnits[] = {
      {"C_Gamma", "N^2 m s (integral of Gamma*^T Gamma* dt per metre walked)"},
      {"C_E", "J/m"}, {"W", "J/m"}, {"C_frott", "J/m"},
      {"cost_of_transport", "1 (C_E / (m g): electrical energy per metre and newton of weight)"},
      {"speed", "m/s"}, {"step_length", "m"},
      {"T_SS", "s"}, {"T_DS", "s"}, {"alphadot_fSS", "rad/s"},
      {"ds_switch_times", "s from the start of double support"},
      {"parameters", "rad, m, s; delta*s_* are d(delta)/d(alpha), alphadot_iSS rad/s"},
      {"constraints", "per group, see 'unit'; satisfied when value <= 1e-6 x the group's scale"},
      {"between_nodes", "worst_value in its group's unit, worst_scaled = value / group scale"},
  };
  w.key("units").beginObject();
  for (const auto& [key, unit] : kUnits) w.key(key).value(unit);
  if (o.parameterisation.landsWithImpact())
    w.key("impact").value("N s (impulses, world frame), J, J/m, rad/s, m/s; X = [q, x_t, z_t]");
  w.endObject();
}

std::string gaitSummaryJson(const GaitEvaluator& ev, const GaitParameters& p,
                            const GaitEvaluation<double>& e,
                            const std::function<void(JsonWriter&)>& extra) {
  JsonWriter w;
  w.beginObject();
  writeGaitSummaryMembers(w, ev, p, e);
  if (extra) extra(w);
  w.endObject();
  return w.str() + "\n";
}

void writeOverridesJson(JsonWriter& w, const std::vector<std::string>& overrides) {
  if (overrides.empty()) return;
  w.key("overrides").beginArray();
  for (const std::string& o : overrides) w.value(o);
  w.endArray();
}

}  // namespace gaitopt
