#pragma once
// MuJoCo plant of the walking controller's validation (examples/mujoco_walk, bench/
// bench_walker): the exported MJCF robot, the controller's sensor view of it, the perturbations,
// the step bookkeeping and the walk loop. Uses the controller through its C interface only.
//
// A step runs from one touchdown (the swing foot landing well ahead of the stance foot after a
// swing) to the next; the first one from the initial state. Per step: duration, length
// (between the stance feet), speed, stance slip. The walk stops after the steps asked for or
// on a fall (the controller says so, the hip low above the stance foot, the trunk tipped, no
// touchdown for long). Walked: every step, and the mean speed of the last half within 5 % of
// the gait's.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "gaitopt/control/walker.h"

namespace mujoco_walk {

// Bad input (exit 2): the message names the file or option and the problem.
struct BadInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline constexpr const char* kJoints[4] = {"knee_left", "hip_left", "hip_right", "knee_right"};
inline constexpr const char* kSides[2] = {"left", "right"};
inline constexpr double kContactForce = 1.0;     // [N] a foot is on the ground above this
inline constexpr double kPushDuration = 0.02;    // [s]
inline constexpr double kSpeedTolerance = 0.05;  // relative, mean speed of the last half
inline constexpr double kHipLowFraction = 0.5;   // fall: hip below this share of its start height
inline constexpr double kTrunkTipped = 1.0;      // fall: |pitch| above this [rad]
inline constexpr double kMinSwingAir = 0.02;     // [s] in the air before a touchdown counts
inline constexpr double kMinStepShare = 0.25;    // a touchdown lands this share of a step ahead

// The simulated walk: plant, steps, controller rate and perturbations (mujoco_walk --help).
struct WalkOptions {
  std::string model;  // MJCF file
  int steps = 100;
  double rate = 1000.0, velocity_scale = 1.0, trunk_mass_scale = 1.0, slope = 0.0, push = 0.0;
};

// Indices of the exported MJCF's parts (src/export/robot_export.cpp): the trunk is the root
// body with slide joints rootx, rootz and the hinge rooty (axis −y, so its value is the
// pitch, > 0 leaning backward); the hips are on the trunk; each tibia carries a foot sphere.
struct Plant {
  mjModel* m = nullptr;
  int root_x = 0, root_z = 0, root_pitch = 0;  // qpos = qvel indices of the root joints
  int qpos[4] = {}, dof[4] = {};               // physical joint order
  int hip_joint = 0, trunk = 0, floor = 0;
  int foot[2] = {}, tibia[2] = {};             // geom, body: left, right
  double foot_radius = 0.0;
  double normal[3] = {0, 0, 1}, tangent[3] = {1, 0, 0};  // floor, + along the walk
  mutable std::vector<mjtNum> jac;                       // scratch of point Jacobians, 3 × nv
};

inline int jointId(const mjModel* m, const std::string& file, const char* name) {
  const int id = mj_name2id(m, mjOBJ_JOINT, name);
  if (id < 0) throw BadInput(file + ": the model has no joint '" + name + "'");
  return id;
}

inline int namedId(const mjModel* m, const std::string& file, mjtObj type,
                   const std::string& name) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw BadInput(file + ": the model has no '" + name + "'");
  return id;
}

inline Plant plantOf(mjModel* m, const std::string& file) {
  Plant p;
  p.m = m;
  p.root_x = m->jnt_qposadr[jointId(m, file, "rootx")];
  p.root_z = m->jnt_qposadr[jointId(m, file, "rootz")];
  const int pitch = jointId(m, file, "rooty");
  if (m->jnt_axis[3 * pitch + 1] != -1.0)
    throw BadInput(file + ": joint 'rooty' must have the axis 0 -1 0 (pitch > 0 leaning back)");
  p.root_pitch = m->jnt_qposadr[pitch];
  if (m->nq != m->nv) throw BadInput(file + ": expected a planar tree of slides and hinges");
  if (m->nu != 4) throw BadInput(file + ": expected 4 actuators, got " + std::to_string(m->nu));
  for (int j = 0; j < 4; ++j) {
    const int id = jointId(m, file, kJoints[j]);
    p.qpos[j] = m->jnt_qposadr[id];
    p.dof[j] = m->jnt_dofadr[id];
    if (m->actuator_trnid[2 * j] != id)
      throw BadInput(file + ": actuator " + std::to_string(j) + " must drive " + kJoints[j]);
  }
  p.hip_joint = jointId(m, file, "hip_left");
  p.trunk = namedId(m, file, mjOBJ_BODY, "trunk");
  p.floor = namedId(m, file, mjOBJ_GEOM, "floor");
  for (int i = 0; i < 2; ++i) {
    p.foot[i] = namedId(m, file, mjOBJ_GEOM, std::string("foot_") + kSides[i]);
    p.tibia[i] = namedId(m, file, mjOBJ_BODY, std::string("tibia_") + kSides[i]);
  }
  p.foot_radius = m->geom_size[3 * p.foot[0]];
  return p;
}

// --trunk-mass-scale: the plant's trunk heavier or lighter than the controller's model.
inline void scaleTrunk(Plant& p, mjData* d, double f) {
  p.m->body_mass[p.trunk] *= f;
  for (int k = 0; k < 3; ++k) p.m->body_inertia[3 * p.trunk + k] *= f;
  mj_setConst(p.m, d);
}

// --slope: the floor plane rotated about the y axis through the origin (the first stance
// foot's centre), + uphill toward +x; gravity stays vertical.
inline void tiltFloor(Plant& p, double slope) {
  const double s = std::sin(slope), c = std::cos(slope), r = p.foot_radius;
  const double n[3] = {-s, 0.0, c}, t[3] = {c, 0.0, s};
  std::copy(n, n + 3, p.normal);
  std::copy(t, t + 3, p.tangent);
  // The plane's surface stays a foot radius below the origin, along its normal.
  mjtNum* pos = p.m->geom_pos + 3 * p.floor;
  pos[0] = r * s;
  pos[1] = 0.0;
  pos[2] = -r * c;
  // Rotation about +y by −slope takes +z to the normal.
  mjtNum* q = p.m->geom_quat + 4 * p.floor;
  q[0] = std::cos(0.5 * slope);
  q[1] = 0.0;
  q[2] = -std::sin(0.5 * slope);
  q[3] = 0.0;
}

inline double dot3(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Height of foot i's sphere above the floor (negative: penetrating).
inline double footClearance(const Plant& p, const mjData* d, int i) {
  const mjtNum* c = d->geom_xpos + 3 * p.foot[i];
  const mjtNum* f = d->geom_xpos + 3 * p.floor;
  const double rel[3] = {c[0] - f[0], c[1] - f[1], c[2] - f[2]};
  return dot3(rel, p.normal) - p.foot_radius;
}

// Switches a foot's collisions with the floor off and back on.
class FootCollision {
 public:
  FootCollision(Plant& p, int foot)
      : p_(p), geom_(p.foot[foot]), type_(p.m->geom_contype[geom_]),
        affinity_(p.m->geom_conaffinity[geom_]) {}
  void disable() {
    p_.m->geom_contype[geom_] = 0;
    p_.m->geom_conaffinity[geom_] = 0;
    disabled_ = true;
  }
  void restore() {
    p_.m->geom_contype[geom_] = type_;
    p_.m->geom_conaffinity[geom_] = affinity_;
    disabled_ = false;
  }
  bool disabled() const { return disabled_; }

 private:
  Plant& p_;
  int geom_, type_, affinity_;
  bool disabled_ = false;
};

// World velocity (x, z) of a point fixed to `body`.
inline std::array<double, 2> pointVelocity(const Plant& p, const mjData* d, const mjtNum* point,
                                           int body) {
  p.jac.resize(3 * p.m->nv);
  mj_jac(p.m, d, p.jac.data(), nullptr, point, body);
  std::array<double, 2> v{0.0, 0.0};
  for (int i = 0; i < p.m->nv; ++i) {
    v[0] += p.jac[i] * d->qvel[i];
    v[1] += p.jac[2 * p.m->nv + i] * d->qvel[i];
  }
  return v;
}

// Normal forces of the floor on each foot [N] (contacts of the last mj_forward/mj_step2).
inline std::array<double, 2> footForces(const Plant& p, const mjData* d) {
  std::array<double, 2> n{0.0, 0.0};
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& k = d->contact[c];
    for (int i = 0; i < 2; ++i) {
      if (k.geom1 != p.foot[i] && k.geom2 != p.foot[i]) continue;
      mjtNum f[6];
      mj_contactForce(p.m, d, c, f);
      n[i] += f[0];
    }
  }
  return n;
}

// The controller's view of the plant: hip = the hip joints' anchor, pitch = rooty.
inline gaitopt_walker_state sensorState(const Plant& p, const mjData* d,
                                        const std::array<double, 2>& force) {
  gaitopt_walker_state s{};
  s.t = d->time;
  const mjtNum* hip = d->xanchor + 3 * p.hip_joint;
  const std::array<double, 2> v = pointVelocity(p, d, hip, p.trunk);
  s.x_hip = hip[0];
  s.z_hip = hip[2];
  s.xd_hip = v[0];
  s.zd_hip = v[1];
  s.pitch = d->qpos[p.root_pitch];
  s.pitchd = d->qvel[p.root_pitch];
  for (int j = 0; j < 4; ++j) {
    s.phi[j] = d->qpos[p.qpos[j]];
    s.phid[j] = d->qvel[p.dof[j]];
  }
  for (int i = 0; i < 2; ++i) s.contact[i] = force[i] > kContactForce ? 1 : 0;
  return s;
}

// MuJoCo state from the controller's initial state: joints and pitch as given, the root
// slides placing the hip anchor at (x_hip, z_hip) with velocity (xd_hip, zd_hip).
inline void setState(const Plant& p, mjData* d, const gaitopt_walker_state& s) {
  mj_resetData(p.m, d);
  d->qpos[p.root_pitch] = s.pitch;
  d->qvel[p.root_pitch] = s.pitchd;
  for (int j = 0; j < 4; ++j) {
    d->qpos[p.qpos[j]] = s.phi[j];
    d->qvel[p.dof[j]] = s.phid[j];
  }
  mj_forward(p.m, d);
  const mjtNum* hip = d->xanchor + 3 * p.hip_joint;
  const std::array<double, 2> v = pointVelocity(p, d, hip, p.trunk);
  // The slides move the hip one to one.
  d->qpos[p.root_x] += s.x_hip - hip[0];
  d->qpos[p.root_z] += s.z_hip - hip[2];
  d->qvel[p.root_x] += s.xd_hip - v[0];
  d->qvel[p.root_z] += s.zd_hip - v[1];
  mj_forward(p.m, d);
}

struct StepStats {
  int step = 0, stance = 0;
  double t0 = 0.0, duration = 0.0, length = 0.0, speed = 0.0;
  double foot_x = 0.0, foot_z = 0.0;  // stance foot (sphere centre) at the step's start
  double slip = 0.0;    // ∫|v_t| dt of the stance foot's contact point while in contact [m]
};

struct Outcome {
  std::vector<StepStats> steps;  // completed steps
  std::string reason;            // empty: all steps walked
  double t_end = 0.0;
  gaitopt_walker_state last{};
};

// Tangential velocity of the tibia's material point at the bottom of the foot sphere: zero
// while the foot rolls without slipping (the sphere centre itself moves by r·angle).
inline double slipVelocity(const Plant& p, const mjData* d, int i) {
  const mjtNum* c = d->geom_xpos + 3 * p.foot[i];
  const mjtNum point[3] = {c[0] - p.foot_radius * p.normal[0], c[1],
                           c[2] - p.foot_radius * p.normal[2]};
  const std::array<double, 2> v = pointVelocity(p, d, point, p.tibia[i]);
  return v[0] * p.tangent[0] + v[1] * p.tangent[2];
}

inline double footX(const Plant& p, const mjData* d, int i) {
  return d->geom_xpos[3 * p.foot[i]];
}
inline double footZ(const Plant& p, const mjData* d, int i) {
  return d->geom_xpos[3 * p.foot[i] + 2];
}

// Walk bookkeeping: touchdowns, steps, the push, the fall checks.
class Walk {
 public:
  Walk(const Plant& p, const gaitopt_walker_info& info, const gaitopt_walker_state& s0,
       const WalkOptions& a)
      : p_(p), info_(info), args_(a) {
    stance_ = s0.contact[0] ? 0 : 1;
    hip_height0_ = s0.z_hip;
    push_step_ = a.steps / 5;
    push_force_ = mj_getTotalmass(p.m) * a.push / kPushDuration;
    stall_time_ = 3.0 * (info.t_ss + info.t_ds) + 0.5;
  }

  void start(const mjData* d) {
    current_.stance = stance_;
    current_.foot_x = footX(p_, d, stance_);
    current_.foot_z = footZ(p_, d, stance_);
    ss_start_ = 0.0;
  }

  // One state (before the step is integrated); false when the walk ends.
  bool observe(const mjData* d, const gaitopt_walker_state& s) {
    const int swing = 1 - stance_;
    const double dt = p_.m->opt.timestep;
    air_ = s.contact[swing] ? 0.0 : air_ + dt;
    lifted_ = lifted_ || air_ >= kMinSwingAir;
    if (s.contact[stance_]) current_.slip += std::abs(slipVelocity(p_, d, stance_)) * dt;
    if (ss_start_ < 0.0 && !s.contact[swing]) ss_start_ = d->time;
    // A scuff of the swing foot is no touchdown: it must land well ahead after a swing.
    if (lifted_ && s.contact[swing] &&
        footX(p_, d, swing) - current_.foot_x > kMinStepShare * info_.step_length)
      touchdown(d, swing);
    if (done()) return false;
    const double hip_above_foot = s.z_hip - footZ(p_, d, stance_);
    if (hip_above_foot < kHipLowFraction * hip_height0_) return fail("hip_low");
    if (std::abs(s.pitch) > kTrunkTipped) return fail("trunk_tipped");
    if (d->time - current_.t0 > stall_time_) return fail("stalled");
    return true;
  }

  // The push force on the trunk now [N] (0 outside the push).
  double pushForce(double t) const {
    if (args_.push == 0.0 || current_.step != push_step_ || ss_start_ < 0.0) return 0.0;
    const double t_push = ss_start_ + 0.5 * info_.t_ss;
    return t >= t_push && t < t_push + kPushDuration ? push_force_ : 0.0;
  }

  bool fail(const std::string& reason) {
    out_.reason = reason;
    return false;
  }
  bool done() const { return static_cast<int>(out_.steps.size()) >= args_.steps; }
  Outcome& outcome() { return out_; }

 private:
  void touchdown(const mjData* d, int foot) {
    current_.duration = d->time - current_.t0;
    current_.length = footX(p_, d, foot) - current_.foot_x;
    current_.speed = current_.length / current_.duration;
    out_.steps.push_back(current_);
    StepStats next;
    next.step = current_.step + 1;
    next.t0 = d->time;
    next.stance = foot;
    next.foot_x = footX(p_, d, foot);
    next.foot_z = footZ(p_, d, foot);
    current_ = next;
    stance_ = foot;
    lifted_ = false;
    air_ = 0.0;
    ss_start_ = -1.0;  // the single support starts when the rear foot lifts
  }

  const Plant& p_;
  const gaitopt_walker_info& info_;
  const WalkOptions& args_;
  Outcome out_;
  StepStats current_;
  int stance_ = 0, push_step_ = 0;
  bool lifted_ = false;
  double hip_height0_ = 0.0, push_force_ = 0.0, stall_time_ = 0.0, ss_start_ = 0.0, air_ = 0.0;
};

using WalkerPtr = std::unique_ptr<gaitopt_walker, void (*)(gaitopt_walker*)>;

// The controller of an export file; BadInput with the controller's message if it does not load.
inline WalkerPtr loadWalker(const std::string& export_path, const std::string& options) {
  char error[2048] = "";
  WalkerPtr w(gaitopt_walker_load(export_path.c_str(), options.empty() ? nullptr : options.c_str(),
                                  error, sizeof error),
              gaitopt_walker_free);
  if (!w) throw BadInput(error[0] ? error : export_path + ": the controller did not load");
  return w;
}

struct Summary {
  bool walked = false;
  int steps = 0;
  double mean_speed = 0.0, speed_error = 0.0, max_slip = 0.0;
  std::string reason;
};

// The last half's mean speed (total length over total time) and the verdict.
inline Summary summarise(const Outcome& o, int planned, double gait_speed) {
  Summary s;
  s.steps = static_cast<int>(o.steps.size());
  double length = 0.0, time = 0.0;
  for (int k = s.steps / 2; k < s.steps; ++k) {
    length += o.steps[k].length;
    time += o.steps[k].duration;
  }
  for (const StepStats& st : o.steps) s.max_slip = std::max(s.max_slip, st.slip);
  s.mean_speed = time > 0.0 ? length / time : 0.0;
  s.speed_error = 100.0 * (s.mean_speed / gait_speed - 1.0);
  s.reason = o.reason;
  if (s.reason.empty() && s.steps < planned) s.reason = "incomplete";
  if (s.reason.empty() && std::abs(s.speed_error) > 100.0 * kSpeedTolerance)
    s.reason = "speed_error";
  s.walked = s.reason.empty();
  return s;
}

// Walks the controller `w` on the plant of `a` from its initial state. With `call_ns`, the
// duration of every gaitopt_walker_torques call [ns] is appended to it.
inline Outcome walkInMujoco(const WalkOptions& a, gaitopt_walker* w,
                            std::vector<double>* call_ns = nullptr) {
  gaitopt_walker_info info{};
  gaitopt_walker_state s0{};
  if (gaitopt_walker_get_info(w, &info) != 0 || gaitopt_walker_initial_state(w, &s0) != 0)
    throw BadInput("the controller gives no gait");
  char error[1000] = "";
  std::unique_ptr<mjModel, void (*)(mjModel*)> model(
      mj_loadXML(a.model.c_str(), nullptr, error, sizeof error), mj_deleteModel);
  if (!model) throw BadInput(a.model + ": MuJoCo: " + error);
  std::unique_ptr<mjData, void (*)(mjData*)> data(mj_makeData(model.get()), mj_deleteData);
  mjData* d = data.get();
  Plant p = plantOf(model.get(), a.model);
  if (a.trunk_mass_scale != 1.0) scaleTrunk(p, d, a.trunk_mass_scale);
  if (a.slope != 0.0) tiltFloor(p, a.slope);

  // --velocity-scale scales every velocity: the stance foot stays at rest.
  s0.xd_hip *= a.velocity_scale;
  s0.zd_hip *= a.velocity_scale;
  s0.pitchd *= a.velocity_scale;
  for (double& v : s0.phid) v *= a.velocity_scale;
  setState(p, d, s0);
  // On a slope the swing foot may start inside the floor behind the stance foot: it does not
  // collide until it is above it.
  const int swing0 = s0.contact[0] ? 1 : 0;
  FootCollision swing_collision(p, swing0);
  if (footClearance(p, d, swing0) < 0.0) swing_collision.disable();

  Walk walk(p, info, s0, a);
  walk.start(d);
  // Contact flags come from the forces of the step before (MuJoCo solves the contact forces
  // with the step), 0.5 ms old.
  std::array<double, 2> force = footForces(p, d);
  const double period = 1.0 / a.rate;
  double next_call = 0.0;
  double tau[4] = {0, 0, 0, 0};
  gaitopt_walker_state s{};
  while (true) {
    mj_step1(p.m, d);
    if (swing_collision.disabled() && footClearance(p, d, swing0) >= 0.0)
      swing_collision.restore();
    s = sensorState(p, d, force);
    if (!walk.observe(d, s)) break;
    if (d->time >= next_call - 1e-9) {
      const auto t0 = std::chrono::steady_clock::now();
      const int status = gaitopt_walker_torques(w, &s, tau);
      if (call_ns)
        call_ns->push_back(
            std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0)
                .count());
      if (status == 1) {
        walk.fail("controller_fallen");
        break;
      }
      for (int j = 0; j < 4; ++j) d->ctrl[j] = tau[j];
      next_call += period;
    }
    d->xfrc_applied[6 * p.trunk] = walk.pushForce(d->time);
    mj_step2(p.m, d);
    force = footForces(p, d);
  }
  Outcome out = walk.outcome();
  out.t_end = d->time;
  out.last = s;
  return out;
}

}  // namespace mujoco_walk
