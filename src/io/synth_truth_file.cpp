#include "gaitopt/io/synth_truth_file.hpp"

#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {

std::string synthTruthJson(const std::string& robot_path, const std::string& gait_path,
                           const std::vector<Effect>& effects, const SynthOptions& o) {
  JsonWriter w;
  w.beginObject();
  w.key("robot").value(robot_path).key("gait").value(gait_path);
  w.key("steps").value(o.steps).key("rate_hz").value(o.rate);
  w.key("seed").value(static_cast<double>(o.seed));
  w.key("noise").beginObject();
  w.key("enabled").value(o.noise).key("encoder_counts_per_rev").value(o.encoder_counts);
  w.key("torque_sd").value(o.torque_noise).key("force_sd").value(o.force_noise);
  w.endObject();
  w.key("effects").beginArray();
  for (const Effect& e : effects) {
    w.beginObject().key("effect").value(effectInfo(e.kind).name).key("joint");
    if (e.joint == kNoJoint) w.null(); else w.value(jointName(e.joint));
    w.key("value").value(e.value).key("unit").value(effectInfo(e.kind).unit);
    w.endObject();
  }
  w.endArray().key("unmodelled").beginArray();
  for (const UnmodelledEffect& e : o.unmodelled) {
    w.beginObject().key("effect").value(unmodelledName(e.kind));
    w.key("joint");
    if (e.joint == kNoJoint) w.null(); else w.value(kPhysicalJointNames[e.joint]);
    w.key("value").value(e.value);
    w.key("unit").value(unmodelledUnit(e.kind)).endObject();
  }
  w.endArray().endObject();
  return w.str() + "\n";
}

}  // namespace gaitopt
