#include "gaitopt/io/opensim_analysis_file.hpp"

#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {

std::string opensimAnalysisJson(const OpenSimAnalysis& a, const ImportedTrial& trial) {
  JsonWriter w;
  w.beginObject();
  w.key("conventions").beginArray();
  for (const std::string& s : trial.conventions.statements) w.value(s);
  w.endArray();
  w.key("notes").beginArray();
  for (const std::string& s : trial.notes) w.value(s);
  w.endArray();
  w.key("belt_speed").value(trial.belt_speed).key("belt_source").value(trial.belt_source);
  w.key("stance_heel_speed");
  if (trial.stance_heel_speed) w.value(*trial.stance_heel_speed);
  else w.null();
  w.key("edge_margin_s").value(a.edge_margin);
  w.key("joint_torques_vs_opensim").beginArray();
  for (const JointComparison& j : a.joints) {
    w.beginObject().key("joint").value(j.joint).key("rms_difference").value(j.rms);
    w.key("reference_rms").value(j.reference_rms).key("correlation").value(j.correlation);
    w.key("samples").value(j.samples).endObject();
  }
  w.endArray();
  w.key("single_support").beginObject();
  w.key("alpha_residual_rms").value(a.alpha_residual_rms).key("cop_moment_rms").value(a.cop_moment_rms);
  w.key("alpha_minus_cop_rms").value(a.alpha_minus_cop_rms);
  w.key("alpha_minus_rocker_rms").value(a.alpha_minus_rocker_rms);
  w.key("correlation").value(a.alpha_cop_correlation).key("samples").value(a.single_support_samples);
  w.endObject();
  w.key("force_residual_rms").beginObject().key("x").value(a.force_residual_rms_x);
  w.key("z").value(a.force_residual_rms_z).endObject();
  const RockerFootReport& r = a.rocker;
  w.key("rocker_foot").beginObject();
  w.key("radius_all").value(r.radius_all).key("radius_right").value(r.radius_right);
  w.key("radius_left").value(r.radius_left).key("stances_right").value(r.stances_right);
  w.key("stances_left").value(r.stances_left);
  w.key("holdout_cop_rms_point_foot").value(r.holdout_rms_point);
  w.key("holdout_cop_rms_rocker").value(r.holdout_rms_rocker).key("holdout_gain_pct").value(r.holdout_gain_pct);
  w.key("leg_length").value(r.leg_length).key("literature_radius").value(r.literature_radius);
  w.key("radius_over_leg_length").value(r.radius_all / r.leg_length);
  w.endObject();
  // Every 5th sample of each stance (120 Hz at 600 Hz plates), for plots.
  w.key("stances").beginArray();
  for (const StanceSamples& st : a.stances) {
    const Eigen::Index m = (st.shank.size() + 4) / 5;
    const auto every5 = [m](const Eigen::VectorXd& v) {
      return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<5>>(v.data(), m));
    };
    w.beginObject().key("side").value(sideName(st.side));
    w.key("shank").value(every5(st.shank)).key("cop_x").value(every5(st.cop_x));
    w.key("vertical_force").value(every5(st.weight)).endObject();
  }
  w.endArray();
  w.endObject();
  return w.str();
}

}  // namespace gaitopt
