#include "gaitopt/io/diagnosis_file.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/robot_extensions.hpp"
#include "gaitopt/io/yaml_reader.hpp"

namespace gaitopt {

namespace {

const std::array<const char*, 6> kSimulationNames = {"alpha",     "knee_left",  "hip_left",
                                                     "hip_right", "knee_right", "overall"};

void channelMap(JsonWriter& w, const std::string& key, const std::array<double, kNumChannels>& v) {
  w.key(key).beginObject();
  for (int c = 0; c < kNumChannels; ++c) w.key(kChannelNames[c]).value(v[c]);
  w.endObject();
}

void channelReportJson(JsonWriter& w, const ChannelReport& r) {
  w.beginObject();
  channelMap(w, "rms", r.rms);
  channelMap(w, "relative_rms", r.relative_rms);
  channelMap(w, "rms_ss", r.rms_ss);
  channelMap(w, "rms_ds", r.rms_ds);
  w.key("normalised_rms").value(r.normalised_rms);
  w.key("simulation_error");
  if (r.simulation_error.size() == 0) {
    w.null();
  } else {
    w.beginObject();
    for (int k = 0; k < 6; ++k) w.key(kSimulationNames[k]).value(r.simulation_error(k));
    w.endObject();
  }
  w.endObject();
}

void inertialJson(JsonWriter& w, const InertialResult& r) {
  w.key("inertial");
  if (!r.tried) {
    w.null();
    return;
  }
  w.beginObject().key("accepted").value(r.accepted).key("p_value").value(r.p_value);
  w.key("method").value(
      "weighted least squares, links physically consistent (m > 0, I > 0, CoM on its link) "
      "by a log-barrier interior-point method; base parameters by QR with column pivoting");
  w.key("rank").value(r.base.rank);
  w.key("holdout_rms").beginObject().key("before").value(r.holdout_rms_before);
  w.key("after").value(r.holdout_rms_after).endObject();
  w.key("base_parameters").beginArray();
  for (int i = 0; i < r.base.rank; ++i) {
    w.beginObject().key("name").value(r.base.label(i));
    w.key("unit").value(kInertialParameterUnits[r.base.independent[i]]);
    w.key("nominal").value(r.base_nominal(i)).key("value").value(r.base_fitted(i));
    w.key("stderr").value(r.base_stderr(i)).endObject();
  }
  w.endArray().key("parameters").beginArray();
  for (int k = 0; k < kNumInertialParameters; ++k) {
    w.beginObject().key("name").value(kInertialParameterNames[k]);
    w.key("unit").value(kInertialParameterUnits[k]);
    w.key("nominal").value(r.nominal(k)).key("value").value(r.fitted(k)).endObject();
  }
  w.endArray().key("active_constraints").beginArray();
  for (const std::string& a : r.active) w.value(a);
  w.endArray().endObject();
}

void jointValue(JsonWriter& w, const Effect& e) {
  w.key("effect").value(effectInfo(e.kind).name).key("joint");
  if (e.joint == kNoJoint) w.null(); else w.value(jointName(e.joint));
  w.key("value").value(e.value);
}

void partialFitJson(JsonWriter& w, const PartialFit& f) {
  w.beginObject();
  if (f.effect.kind == EffectKind::Inertial) {
    w.key("effect").value("inertial").key("joint").null().key("value").null();
  } else {
    jointValue(w, f.effect);
  }
  w.key("p_value").value(f.p_value).key("reason").value(f.reason).endObject();
}

std::string fmt(double v, const char* f = "%.3g") {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string jointPhrase(int channel) {
  static const std::array<const char*, kNumChannels> phrases = {
      "single-support foot moment (alpha row)", "left-knee torque", "left-hip torque",
      "right-hip torque", "right-knee torque", "horizontal stance-foot reaction",
      "vertical stance-foot reaction", "horizontal rear-foot reaction",
      "vertical rear-foot reaction", "rear-foot height in double support",
      "stance-foot centre-of-pressure travel"};
  return phrases[channel];
}

std::string causePhrase(const Cause& c) {
  const EffectInfo& info = effectInfo(c.effect.kind);
  const std::string value = fmt(c.effect.value) + " ± " + fmt(c.stderr_, "%.2g");
  const std::string on = c.effect.joint == kNoJoint ? "" : " on " + jointName(c.effect.joint);
  switch (c.effect.kind) {
    case EffectKind::Coulomb: return "an extra Coulomb friction of " + value + " N·m" + on;
    case EffectKind::Viscous: return "an extra viscous friction of " + value + " N·m·s/rad" + on;
    case EffectKind::RotorInertia: return "a rotor inertia " + value + " times the nominal" + on;
    case EffectKind::TorqueOffset: return "a torque-sensor offset of " + value + " N·m" + on;
    case EffectKind::TorqueGain: return "a torque-sensor gain of " + value + on;
    case EffectKind::EncoderOffset: return "an encoder offset of " + value + " rad" + on;
    case EffectKind::Backlash: return "a backlash of " + value + " rad" + on;
    case EffectKind::Payload: return "an extra mass of " + value + " kg at the hip";
    case EffectKind::TrunkCom: return "a trunk centre of mass moved by " + value + " m along the trunk";
    case EffectKind::Slope: return "a ground slope of " + value + " rad";
    case EffectKind::RockerFoot:
      return "a foot that rolls like an arc of radius " + value + " m instead of touching the "
             "ground at one point (the point foot is the cause)";
    case EffectKind::FootOffset:
      return "a foot whose contact point lies " + value + " m ahead of the ankle (the point "
             "foot is the cause)";
    case EffectKind::Inertial:
      return "link inertial parameters differing from the robot file's (a physically consistent "
             "fit of the base inertial parameters, section Inertial)";
  }
  return info.name;
}

// "a residual of 2.1 N·m on knee_right that follows its angle".
std::string unexplainedPhrase(const Unexplained& u) {
  const bool joint = u.joint != kNoJoint;
  const std::string of = joint ? "the " + jointName(u.joint) + " " : "the joint ";
  std::string follows;
  switch (u.signature) {
    case Signature::JointAngle: follows = of + (joint ? "angle" : "angles"); break;
    case Signature::Velocity: follows = of + (joint ? "velocity" : "velocities"); break;
    case Signature::Acceleration: follows = of + (joint ? "acceleration" : "accelerations"); break;
    case Signature::Torque: follows = of + (joint ? "torque" : "torques"); break;
    case Signature::TorqueShift: follows = "a time shift of " + of + (joint ? "torque" : "torques"); break;
    case Signature::None: follows = "none of the joint angles, velocities, accelerations or torques"; break;
  }
  return "a residual of " + fmt(u.heldout_rms) + " " + kChannelUnits[u.channel] + " (RMS; noise " +
         fmt(u.noise_rms) + ") on " + kChannelNames[u.channel] + " that follows " + follows;
}

// "…; a residual … is not explained by any effect of the library (the partial fits)": the
// reason of a best fit out of range in full, the candidates that leave the residual structured
// by name.
std::string unexplainedSentence(const Diagnosis& d) {
  std::string out, reasons, leaving;
  for (std::size_t k = 0; k < d.unexplained.size(); ++k) {
    out += (k == 0 ? "" : k + 1 == d.unexplained.size() ? " and " : ", ") + unexplainedPhrase(d.unexplained[k]);
    for (const PartialFit& f : d.unexplained[k].partial_fits) {
      const bool structured = f.reason.find("structured residual") != std::string::npos ||
                              f.reason.find("mimic") != std::string::npos;
      std::string& list = structured ? leaving : reasons;
      const std::string item = structured ? effectLabel(f.effect) : f.reason;
      if (list.find(item) == std::string::npos) list += (list.empty() ? "" : structured ? ", " : "; ") + item;
    }
  }
  out += std::string(d.unexplained.size() > 1 ? " are" : " is") + " not explained by any effect of the library";
  const bool one = leaving.find(',') == std::string::npos;
  if (!leaving.empty())
    reasons += (reasons.empty() ? "" : "; ") + leaving + (one ? " reduces it but leaves" : " reduce it but leave") +
               " a structured residual";
  return reasons.empty() ? out : out + " (" + reasons + ")";
}

void gainIntervalJson(JsonWriter& w, const std::string& key, const GainInterval& g) {
  w.key(key).beginObject().key("pct").value(g.pct).key("low_pct").value(g.low_pct);
  w.key("high_pct").value(g.high_pct).key("steps").value(g.steps).endObject();
}

// "45 % [30, 60] %, every step left out in turn" or "" when not computed.
std::string stepGainPhrase(const GainInterval& g) {
  if (!std::isfinite(g.pct)) return "";
  return fmt(g.pct, "%.0f") + " % (95 % interval " + fmt(g.low_pct, "%.0f") + " to " +
         fmt(g.high_pct, "%.0f") + " %) with every step left out in turn";
}

}  // namespace

std::string diagnosisJson(const Diagnosis& d) {
  JsonWriter w;
  w.beginObject();
  w.key("smoothing").value(d.smoothing);
  w.key("nominal");
  channelReportJson(w, d.nominal);
  w.key("nominal_all_steps");
  channelReportJson(w, d.nominal_all);
  w.key("cause").beginArray();
  for (const Cause& c : d.causes) {
    w.beginObject();
    jointValue(w, c.effect);
    w.key("stderr").value(c.stderr_).key("unit").value(effectInfo(c.effect.kind).unit);
    w.key("p_value").value(c.p_value);
    gainIntervalJson(w, "heldout_gain", c.step_gain);
    w.key("confounded_with").beginArray();
    for (const std::string& s : c.confounded_with) w.value(s);
    w.endArray().endObject();
  }
  w.endArray();
  w.key("unexplained").beginArray();
  for (const Unexplained& u : d.unexplained) {
    w.beginObject().key("channel").value(kChannelNames[u.channel]).key("joint");
    if (u.joint == kNoJoint) w.null(); else w.value(jointName(u.joint));
    w.key("heldout_rms").value(u.heldout_rms).key("noise_rms").value(u.noise_rms);
    w.key("unit").value(kChannelUnits[u.channel]);
    w.key("p_value").value(u.p_value).key("signature").value(signatureName(u.signature));
    w.key("partial_fits").beginArray();
    for (const PartialFit& f : u.partial_fits) partialFitJson(w, f);
    w.endArray().endObject();
  }
  w.endArray();
  w.key("partial_fits").beginArray();
  for (const PartialFit& f : d.partial_fits) partialFitJson(w, f);
  w.endArray();
  w.key("candidates").beginArray();
  for (const CandidateResult& c : d.candidates) {
    w.beginObject();
    jointValue(w, c.effect);
    w.key("stderr").value(c.stderr_).key("bic").value(c.bic).key("holdout_rms").value(c.holdout_rms);
    w.key("p_value").value(c.p_value).endObject();
  }
  w.endArray();
  w.key("extended");
  channelReportJson(w, d.extended);
  w.key("gain").beginObject();
  channelMap(w, "rms_reduction_pct", d.rms_reduction_pct);
  w.key("overall_pct").value(d.overall_pct);
  w.key("effect_channels").beginArray();
  for (int c : d.effect_channels) w.value(kChannelNames[c]);
  w.endArray().key("effect_channels_pct").value(d.effect_channels_pct);
  w.key("simulation_error_reduction_pct").value(d.simulation_error_reduction_pct);
  gainIntervalJson(w, "leave_one_step_out", d.step_gain);
  w.endObject();
  inertialJson(w, d.inertial);
  w.key("centre_of_pressure").beginObject().key("used").value(d.cop.used);
  w.key("radius_cop").value(d.cop.radius_cop).key("radius_cop_stderr").value(d.cop.radius_cop_stderr);
  w.key("radius_fit").value(d.cop.radius_fit).key("radius_fit_stderr").value(d.cop.radius_fit_stderr);
  w.key("radius_fit_is_cause").value(d.cop.fit_is_cause);
  w.key("difference_pct").value(d.cop.difference_pct).endObject();
  w.endObject();
  return w.str() + "\n";
}

std::string residualsCsv(const MeasuredData& data, const Diagnosis& d) {
  std::ostringstream out;
  CsvRow header;
  header.texts({"t", "step", "phase", "stance", "heldout"});
  for (const char* tag : {"nominal", "extended"})
    for (int c = 0; c < kNumChannels; ++c) header.text(std::string(kChannelNames[c]) + '_' + tag);
  out << header.line();
  for (std::size_t i = 0; i < data.size(); ++i) {
    CsvRow row;
    row.number(data.t[i]).integer(data.step[i]);
    row.text(data.phase[i] == Phase::SingleSupport ? "SS" : "DS");
    row.text(data.stance[i] == Stance::Left ? "left" : "right").integer(d.holdout_rows[i] ? 1 : 0);
    for (const ResidualMatrix* r : {&d.nominal_residuals, &d.extended_residuals})
      for (int c = 0; c < kNumChannels; ++c) row.number(finiteOrAbsent((*r)(i, c)));
    out << row.line();
  }
  return out.str();
}

void inertialReport(std::ostream& out, const InertialResult& r) {
  out << "\n## Inertial (last resort: no named effect left is significant)\n\n"
      << (r.accepted ? "Accepted" : "Not accepted") << ": p = " << fmt(r.p_value, "%.2g")
      << " (χ² with " << r.base.rank << " degrees of freedom), held-out normalised RMS "
      << fmt(r.holdout_rms_before) << " → " << fmt(r.holdout_rms_after)
      << ". Base parameters (QR with column pivoting of the stacked regressor; the others are "
         "regrouped into them):\n\n| base parameter | unit | nominal | fitted | stderr |\n"
         "|---|---|---|---|---|\n";
  for (int i = 0; i < r.base.rank; ++i)
    out << "| " << r.base.label(i) << " | " << kInertialParameterUnits[r.base.independent[i]]
        << " | " << fmt(r.base_nominal(i), "%.4g") << " | " << fmt(r.base_fitted(i), "%.4g")
        << " | " << fmt(r.base_stderr(i), "%.2g") << " |\n";
  out << "\nPhysical consistency (m > 0, I > 0, CoM on its link) enforced by a log-barrier "
         "interior-point least squares; binding constraints: ";
  for (const std::string& a : r.active) out << "`" << a << "` ";
  out << (r.active.empty() ? "none" : "(the unconstrained fit was not physical)") << ".\n";
}

std::string diagnosisReport(const Diagnosis& d) {
  std::ostringstream out;
  out << "# Diagnosis\n\n";
  if (d.causes.empty() && !d.unexplained.empty()) {
    out << "The model's predictions disagree with the measurements beyond the noise: "
        << unexplainedSentence(d) << ".\n\n";
  } else if (d.causes.empty()) {
    out << "The model's predictions agree with the measurements within the noise: no candidate "
           "effect is significant at 1 % with a held-out gain.\n\n";
  } else {
    // The channel the first cause changes most (nominal − extended RMS on held-out steps).
    int channel = 0;
    double change = -1.0;
    for (int c = 0; c < kNumChannels; ++c) {
      const double delta = d.nominal.rms[c] - d.extended.rms[c];
      if (std::isfinite(delta) && delta / d.nominal.rms[c] > change) {
        change = delta / d.nominal.rms[c];
        channel = c;
      }
    }
    double mean = 0.0, square = 0.0, n = 0.0;  // of the prediction change, held-out steps
    for (Eigen::Index i = 0; i < d.nominal_residuals.rows(); ++i) {
      const double a = d.nominal_residuals(i, channel), b = d.extended_residuals(i, channel);
      if (std::isfinite(a) && std::isfinite(b) && d.holdout_rows[i]) {
        mean += a - b;
        square += (a - b) * (a - b);
        n += 1.0;
      }
    }
    mean /= std::max(1.0, n);
    out << "The model " << (mean >= 0.0 ? "underestimates" : "overestimates") << " the "
        << jointPhrase(channel) << " by " << fmt(std::sqrt(square / std::max(1.0, n))) << " "
        << kChannelUnits[channel] << " (RMS): " << causePhrase(d.causes[0]) << " explains it";
    for (std::size_t k = 1; k < d.causes.size(); ++k) out << ", with " << causePhrase(d.causes[k]);
    out << "; predictions on held-out steps improve by " << fmt(d.effect_channels_pct, "%.0f")
        << " % on the channels the causes act on (" << fmt(d.overall_pct, "%.0f")
        << " % over all channels, " << fmt(d.rms_reduction_pct[channel], "%.0f")
        << " % on that channel"
        << (std::isfinite(d.step_gain.pct) ? "; " + stepGainPhrase(d.step_gain) : "") << ")"
        << (d.unexplained.empty() ? "" : "; " + unexplainedSentence(d)) << ".\n\n";
  }
  out << "## Causes\n\n";
  for (const Cause& c : d.causes) {
    out << "- `" << effectLabel(c.effect) << "` ";
    if (c.effect.kind == EffectKind::Inertial)
      out << "(base parameters in the Inertial section)";
    else
      out << "= " << fmt(c.effect.value, "%.4g") << " ± " << fmt(c.stderr_, "%.2g") << " "
          << effectInfo(c.effect.kind).unit;
    out << ", p = " << fmt(c.p_value, "%.2g");
    if (std::isfinite(c.step_gain.pct)) out << "; held-out gain " << stepGainPhrase(c.step_gain);
    if (!c.confounded_with.empty()) {
      out << "; the data cannot tell it from:";
      for (const std::string& s : c.confounded_with) out << " `" << s << "`";
    }
    out << "\n";
  }
  if (d.causes.empty()) out << "none\n";
  if (d.cop.used)
    out << "\nThe measured centres of pressure are used (channel cop1x): rocker radius from them alone "
        << fmt(d.cop.radius_cop) << " ± " << fmt(d.cop.radius_cop_stderr, "%.2g") << " m, fitted "
        << fmt(d.cop.radius_fit) << " ± " << fmt(d.cop.radius_fit_stderr, "%.2g") << " m ("
        << (d.cop.fit_is_cause ? "the rocker_foot cause" : "the rocker_foot candidate, not a cause")
        << "), " << fmt(d.cop.difference_pct, "%+.0f") << " %.\n";
  out << "\n## Not explained\n\n";
  for (const Unexplained& u : d.unexplained)
    out << "- `" << kChannelNames[u.channel] << "`: held-out RMS " << fmt(u.heldout_rms) << " "
        << kChannelUnits[u.channel] << " against noise " << fmt(u.noise_rms) << ", p = "
        << fmt(u.p_value, "%.2g") << ", follows: " << signatureName(u.signature) << "\n";
  if (d.unexplained.empty()) out << "none: no channel keeps a significant structured residual\n";
  if (!d.partial_fits.empty()) out << "\nLibrary candidates that are not causes:\n\n";
  for (const PartialFit& f : d.partial_fits) out << "- " << f.reason << "\n";
  out << "\n## Held-out steps: RMS per channel (nominal → extended)\n\n"
         "| channel | unit | nominal | extended | reduction % |\n|---|---|---|---|---|\n";
  for (int c = 0; c < kNumChannels; ++c)
    out << "| " << kChannelNames[c] << " | " << kChannelUnits[c] << " | " << fmt(d.nominal.rms[c])
        << " | " << fmt(d.extended.rms[c]) << " | " << fmt(d.rms_reduction_pct[c], "%.1f") << " |\n";
  if (d.nominal.simulation_error.size())
    out << "\nOpen-loop single-support simulation error (RMS over all angles): "
        << fmt(d.nominal.simulation_error(5)) << " rad → " << fmt(d.extended.simulation_error(5))
        << " rad (" << fmt(d.simulation_error_reduction_pct, "%.0f") << " % lower).\n";
  if (!d.effect_channels.empty()) {
    out << "\nChannels the causes act on (90 % of the change in the predictions):";
    for (int c : d.effect_channels) out << " " << kChannelNames[c];
    out << "; their noise-normalised held-out RMS drops by " << fmt(d.effect_channels_pct, "%.1f")
        << " %.\n";
  }
  if (d.inertial.tried) inertialReport(out, d.inertial);
  out << "\nPreprocessing: " << d.smoothing << ".\n";
  return out.str();
}

std::string extendedRobotYaml(const std::string& robot_path, const RobotParams& extended) {
  YAML::Node root = loadYamlFile(robot_path);
  for (const char* key : {"joint_extras", "sensors", "hip_payload", "trunk_com_shift", "ground_slope",
                          "foot_radius", "foot_offset"})
    root.remove(key);
  // The fitted inertial parameters; the file's own text where they were not fitted.
  const auto set = [&](const char* map, const std::string& key, double value) {
    YAML::Node node = root[map][key];
    if (node.as<double>() != value) node = value;
  };
  for (int i = 0; i < 5; ++i) {
    const std::string n = std::to_string(i + 1);
    set("masses", "m" + n, extended.mass[i]);
    set("com_offsets", "s" + n, extended.s[i]);
    set("inertias", "I" + n, extended.inertia[i]);
  }
  YAML::Emitter emit;
  emit.SetDoublePrecision(17);
  emit << root;
  return "# " + robot_path + " extended by gaitopt diagnose with the identified effects\n" +
         std::string(emit.c_str()) + "\n" + robotExtensionsYaml(extended);
}

DiagnosisDocuments diagnosisDocuments(const std::string& robot_path, const MeasuredData& data,
                                      const Diagnosis& d) {
  return {diagnosisJson(d), residualsCsv(data, d), diagnosisReport(d),
          extendedRobotYaml(robot_path, d.extended_robot)};
}

std::vector<std::string> diagnosisFileNames() {
  return {"diagnosis.json", "residuals.csv", "report.md", "extended_robot.yaml"};
}

void writeDiagnosisFiles(const std::string& dir, const DiagnosisDocuments& documents) {
  const std::vector<std::string> names = diagnosisFileNames();
  const std::array<const std::string*, 4> texts = {&documents.json, &documents.residuals_csv,
                                                   &documents.report,
                                                   &documents.extended_robot_yaml};
  for (std::size_t k = 0; k < texts.size(); ++k) writeNewFile(dir + "/" + names[k], *texts[k]);
}

}  // namespace gaitopt
