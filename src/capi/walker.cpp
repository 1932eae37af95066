// The C interface of the reference walker (control/walker.h) over the C++ library: loads the
// JSON export, rebuilds the gait and the controller's model from the robot and gait files it
// embeds, and runs control/walker.hpp. No C++ exception crosses the interface.
#include "gaitopt/control/walker.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <memory>
#include <string>

#include "gaitopt/control/walker.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/io/controller_export_file.hpp"
#include "gaitopt/io/yaml_reader.hpp"

struct gaitopt_walker {
  gaitopt::ControllerExport source;
  gaitopt::Walker walker;
};

namespace {

using gaitopt::Vec2;
using gaitopt::Vec4;

void copyMessage(const std::string& text, char* out, int size) {
  if (!out || size <= 0) return;
  const std::size_t n = std::min(text.size(), static_cast<std::size_t>(size - 1));
  std::memcpy(out, text.data(), n);
  out[n] = '\0';
}

// The `options` mapping over the gait's own controller options.
gaitopt::WalkerOptions walkerOptions(const char* text, gaitopt::WalkerOptions o) {
  if (!text || std::string(text).find_first_not_of(" \t\r\n") == std::string::npos) return o;
  const gaitopt::YamlMap m(gaitopt::parseYamlText(text, "options"), "options", "");
  const auto positive = [&](const std::string& key, double& value) {
    if (const std::optional<double> v = m.optionalNumber(key)) {
      if (!(*v > 0.0)) throw m.error(key, "must be > 0, got " + m.text(key));
      value = *v;
    }
  };
  const auto non_negative = [&](const std::string& key, double& value) {
    if (const std::optional<double> v = m.optionalNumber(key)) {
      if (!(*v >= 0.0)) throw m.error(key, "must be >= 0, got " + m.text(key));
      value = *v;
    }
  };
  positive("gain_scale", o.gain_scale);
  positive("bandwidth", o.bandwidth);
  non_negative("lean_gain", o.lean_gain);
  non_negative("lean_integral_gain", o.lean_integral_gain);
  positive("max_lean", o.max_lean);
  non_negative("slope_compensation", o.slope_compensation);
  non_negative("slope_deadband", o.slope_deadband);
  non_negative("apex_energy_fraction", o.apex_energy_fraction);
  if (m.has("ds_control")) {
    const std::string c = m.string("ds_control");
    if (c != "cubic" && c != "time_optimal")
      throw m.error("ds_control", "expected cubic or time_optimal, got '" + c + "'");
    o.ds_control = c == "cubic" ? gaitopt::DsAlphaControl::Cubic
                                : gaitopt::DsAlphaControl::TimeOptimal;
  }
  if (m.has("torque_limits")) o.torque_limits = m.boolean("torque_limits");
  m.rejectUnknownKeys();
  return o;
}

std::unique_ptr<gaitopt_walker> load(const char* path, const char* options) {
  gaitopt::ControllerExport ex = gaitopt::readControllerExport(path);
  const gaitopt::GaitFile& g = ex.gait;
  const gaitopt::GaitEvaluator evaluator(g.robot, g.options, g.model_options);
  gaitopt::GaitEvaluation<double> e = evaluator.evaluate(g.parameters);
  if (!e.defined() || !e.motion_computed)
    throw std::runtime_error(std::string(path) + ": the exported gait is undefined");
  gaitopt::Model model = gaitopt::buildModel(g.robot, g.model_options);
  const gaitopt::WalkerOptions o =
      walkerOptions(options, gaitopt::walkerOptionsFor(g.options, model));
  gaitopt::Walker walker(std::move(model), std::move(e), g.options.parameterisation, o);
  return std::unique_ptr<gaitopt_walker>(new gaitopt_walker{std::move(ex), std::move(walker)});
}

gaitopt::WalkerState stateOf(const gaitopt_walker_state& s) {
  gaitopt::WalkerState w;
  w.t = s.t;
  w.hip = Vec2(s.x_hip, s.z_hip);
  w.hip_rate = Vec2(s.xd_hip, s.zd_hip);
  w.pitch = s.pitch;
  w.pitch_rate = s.pitchd;
  w.phi = Eigen::Map<const Vec4>(s.phi);
  w.phi_rate = Eigen::Map<const Vec4>(s.phid);
  w.contact = {s.contact[0] != 0, s.contact[1] != 0};
  return w;
}

}  // namespace

extern "C" {

gaitopt_walker* gaitopt_walker_load(const char* export_path, const char* options, char* error,
                                    int error_size) {
  copyMessage("", error, error_size);
  if (!export_path) {
    copyMessage("gaitopt_walker_load: export_path is NULL", error, error_size);
    return nullptr;
  }
  try {
    return load(export_path, options).release();
  } catch (const std::exception& e) {
    copyMessage(e.what(), error, error_size);
  } catch (...) {
    copyMessage(std::string(export_path) + ": unknown error", error, error_size);
  }
  return nullptr;
}

int gaitopt_walker_initial_state(const gaitopt_walker* w, gaitopt_walker_state* out) {
  if (!w || !out) return -1;
  const gaitopt::WalkerState s = w->walker.initialState();
  *out = gaitopt_walker_state{};
  out->t = s.t;
  out->x_hip = s.hip(0);
  out->z_hip = s.hip(1);
  out->xd_hip = s.hip_rate(0);
  out->zd_hip = s.hip_rate(1);
  out->pitch = s.pitch;
  out->pitchd = s.pitch_rate;
  Eigen::Map<Vec4>(out->phi) = s.phi;
  Eigen::Map<Vec4>(out->phid) = s.phi_rate;
  out->contact[0] = s.contact[0];
  out->contact[1] = s.contact[1];
  return 0;
}

int gaitopt_walker_get_info(const gaitopt_walker* w, gaitopt_walker_info* out) {
  if (!w || !out) return -1;
  *out = gaitopt_walker_info{};
  out->speed = w->source.speed;
  out->step_length = w->source.step_length;
  out->t_ss = w->source.t_ss;
  out->t_ds = w->source.t_ds;
  std::fill(out->torque_max, out->torque_max + 4, w->walker.model().robot.envelope.torque[0]);
  copyMessage(w->source.gait.robot_path, out->robot_file, sizeof out->robot_file);
  return 0;
}

double gaitopt_walker_speed(const gaitopt_walker* w) { return w ? w->source.speed : 0.0; }

int gaitopt_walker_torques(gaitopt_walker* w, const gaitopt_walker_state* s, double tau[4]) {
  if (!w || !s || !tau) return -1;
  try {
    const gaitopt::WalkerCommand c = w->walker.torques(stateOf(*s));
    std::copy(c.tau.data(), c.tau.data() + 4, tau);
    return c.fallen ? 1 : 0;
  } catch (...) {
    std::fill(tau, tau + 4, 0.0);
    return 1;
  }
}

void gaitopt_walker_free(gaitopt_walker* w) { delete w; }

}  // extern "C"
