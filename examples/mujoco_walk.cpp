// Plays an exported multi-step gait (gaitopt export) on an exported MJCF robot (gaitopt
// export-model) in MuJoCo: floating base, ground contact with friction, feedforward τ_J plus a
// PD on the motor angles φ_J. The reference is indexed by the phase variable α (the leg-1
// tibia angle measured in the simulation, as in §4.3.1 of the thesis: α replaces time), or by
// time. Prints one line per step (speed, length, duration, tracking error, stance-foot slip
// and lift) and a summary; exit 0 when every step was walked without falling and the mean
// speed is within the tolerance of the gait's, 3 otherwise, 2 on bad input.
//
//   mujoco_walk --model rabbit.xml --trajectory walk.csv [--kp 1500] [--kd 30]
//               [--index alpha|time] [--speed-tolerance 0.05] [--steps-csv FILE]
#include <mujoco/mujoco.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/io/atomic_file.hpp"
#include "gaitopt/io/config_error.hpp"

namespace {

using gaitopt::ExportRow;
using gaitopt::Leg;
using gaitopt::Phase;

// Rows of one phase of one step: α decreases along them.
struct Segment {
  std::vector<ExportRow> rows;
  Leg leg1() const { return rows.front().stance; }
};

std::vector<Segment> segmentsOf(const std::vector<ExportRow>& rows) {
  std::vector<Segment> s;
  for (const ExportRow& r : rows) {
    if (s.empty() || s.back().rows.back().step != r.step || s.back().rows.back().phase != r.phase)
      s.emplace_back();
    s.back().rows.push_back(r);
  }
  return s;
}

// Reference at a phase value: linear interpolation between rows, by α (decreasing) or by t.
struct Reference {
  Eigen::Vector4d phi, phid, tau;
  bool past_end;
};

Reference interpolate(const ExportRow& a, const ExportRow& b, double w) {
  return {(1 - w) * a.phi + w * b.phi, (1 - w) * a.phid + w * b.phid,
          (1 - w) * a.tau + w * b.tau, false};
}

Reference referenceAt(const Segment& seg, bool by_alpha, double alpha, double alphad, double t) {
  const std::vector<ExportRow>& r = seg.rows;
  const auto key = [by_alpha](const ExportRow& x) { return by_alpha ? -x.alpha : x.t; };
  const double k = by_alpha ? -alpha : t;
  if (k >= key(r.back())) return {r.back().phi, r.back().phid, r.back().tau, true};
  if (k <= key(r.front())) return {r.front().phi, r.front().phid, r.front().tau, false};
  const auto it = std::upper_bound(r.begin(), r.end(), k,
                                   [&](double v, const ExportRow& x) { return v < key(x); });
  const ExportRow& hi = *it;
  const ExportRow& lo = *(it - 1);
  const double w = (k - key(lo)) / (key(hi) - key(lo));
  Reference ref = interpolate(lo, hi, w);
  // α replaces time: φ̇_ref = (dφ/dα) α̇ with the measured α̇ (thesis §4.3.1).
  if (by_alpha) ref.phid *= alphad / ((1 - w) * lo.alphad + w * hi.alphad);
  return ref;
}

struct Robot {
  const mjModel* m;
  int qpos[4], dof[4];           // physical joint order (kPhysicalJoints)
  int foot_site[2], tibia[2];    // left, right
  double hip_depth;              // trunk-with-bar CoM above the hip
  double foot_radius;
};

Robot robotOf(const mjModel* m) {
  Robot r{m, {}, {}, {}, {}, 0.0, 0.0};
  for (int j = 0; j < 4; ++j) {
    const int id = mj_name2id(m, mjOBJ_JOINT, gaitopt::kPhysicalJoints[j]);
    if (id < 0) throw std::runtime_error(std::string("model has no joint ") +
                                         gaitopt::kPhysicalJoints[j]);
    r.qpos[j] = m->jnt_qposadr[id];
    r.dof[j] = m->jnt_dofadr[id];
  }
  const char* side[2] = {"left", "right"};
  for (int i = 0; i < 2; ++i) {
    r.foot_site[i] = mj_name2id(m, mjOBJ_SITE, (std::string("foot_") + side[i]).c_str());
    r.tibia[i] = mj_name2id(m, mjOBJ_BODY, (std::string("tibia_") + side[i]).c_str());
    if (r.foot_site[i] < 0 || r.tibia[i] < 0) throw std::runtime_error("model has no feet");
  }
  r.hip_depth = -m->body_pos[3 * mj_name2id(m, mjOBJ_BODY, "femur_left") + 2];
  r.foot_radius = m->geom_size[3 * mj_name2id(m, mjOBJ_GEOM, "foot_left")];
  return r;
}

int side(Leg l) { return l == Leg::Left ? 0 : 1; }

Eigen::Vector2d footOf(const Robot& r, const mjData* d, Leg l) {
  const double* p = d->site_xpos + 3 * r.foot_site[side(l)];
  return {p[0], p[2]};
}

// Horizontal velocity of the tibia's material point at the bottom of the foot sphere: zero
// while the foot rolls without slipping (the sphere centre itself moves by r·Δα).
double slipVelocity(const Robot& r, const mjData* d, Leg l) {
  const double* c = d->site_xpos + 3 * r.foot_site[side(l)];
  mjtNum point[3] = {c[0], c[1], c[2] - r.foot_radius};
  std::vector<mjtNum> jac(3 * r.m->nv);
  mj_jac(r.m, d, jac.data(), nullptr, point, r.tibia[side(l)]);
  double v = 0.0;
  for (int i = 0; i < r.m->nv; ++i) v += jac[i] * d->qvel[i];
  return v;
}

// Leg-l tibia from the vertical and its rate (planar angle of knee → foot, + π/2).
void tibiaAngle(const Robot& r, const mjData* d, Leg l, double& alpha, double& alphad) {
  const double* knee = d->xpos + 3 * r.tibia[side(l)];
  const Eigen::Vector2d f = footOf(r, d, l);
  alpha = std::atan2(f(1) - knee[2], f(0) - knee[0]) + 0.5 * M_PI;
  mjtNum v[6];
  mj_objectVelocity(r.m, d, mjOBJ_BODY, r.tibia[side(l)], v, 0);
  alphad = -v[1];  // a positive planar rate is a rotation about −y
}

// Initial state from the first row: joints and trunk as exported, root velocity such that the
// stance foot is at rest.
void setInitialState(const Robot& r, mjData* d, const ExportRow& row) {
  const mjModel* m = r.m;
  mj_resetData(m, d);
  const double a = row.trunk_angle;
  d->qpos[0] = row.hip(0) - r.hip_depth * std::sin(a);
  d->qpos[1] = row.hip(1) + r.hip_depth * std::cos(a);
  d->qpos[2] = a;
  for (int j = 0; j < 4; ++j) {
    d->qpos[r.qpos[j]] = row.phi(j);
    d->qvel[r.dof[j]] = row.phid(j);
  }
  // Trunk rate α̇ + δ̇1 − δ̇2 = α̇ + φ̇_knee + φ̇_hip of leg 1 (1.13).
  const int k = row.stance == Leg::Left ? 0 : 3, h = row.stance == Leg::Left ? 1 : 2;
  d->qvel[2] = row.alphad + row.phid(k) + row.phid(h);
  d->qvel[0] = d->qvel[1] = 0.0;
  mj_forward(m, d);
  std::vector<mjtNum> jac(3 * m->nv);
  mj_jacSite(m, d, jac.data(), nullptr, r.foot_site[side(row.stance)]);
  double vx = 0.0, vz = 0.0;
  for (int i = 0; i < m->nv; ++i) {
    vx += jac[i] * d->qvel[i];
    vz += jac[2 * m->nv + i] * d->qvel[i];
  }
  d->qvel[0] = -vx;  // ∂foot/∂rootx = (1, 0), ∂foot/∂rootz = (0, 1)
  d->qvel[1] = -vz;
  mj_forward(m, d);
}

struct StepStats {
  int step = 0;
  double t0 = 0.0, duration = 0.0, length = 0.0, speed = 0.0;
  double max_error = 0.0;
  double slip = 0.0;  // ∫|v_x| dt of the stance foot's contact point over single support
  double lift = 0.0;  // highest rise of the stance foot over single support
  Eigen::Vector2d foot0 = Eigen::Vector2d::Zero();
};

struct Args {
  std::string model, trajectory, steps_csv;
  double kp = 1500.0, kd = 30.0, speed_tolerance = 0.05;
  std::string index = "alpha";
  bool ds_by_time = false;
};

bool fallen(const mjData* d) {
  return d->qpos[1] < 0.5 || std::abs(d->qpos[2]) > 1.0;  // trunk CoM low or trunk tipped
}

std::string stepsTable(const std::vector<StepStats>& steps) {
  std::ostringstream o;
  o << "step,t_start,duration,length,speed,max_tracking_error,stance_slip,stance_lift\n";
  for (const StepStats& s : steps)
    o << s.step << ',' << s.t0 << ',' << s.duration << ',' << s.length << ',' << s.speed << ','
      << s.max_error << ',' << s.slip << ',' << s.lift << '\n';
  return o.str();
}

int run(const Args& a) {
  const gaitopt::ExportCsvFile traj = gaitopt::readExportCsv(a.trajectory);
  char error[1000] = "";
  std::unique_ptr<mjModel, void (*)(mjModel*)> m(
      mj_loadXML(a.model.c_str(), nullptr, error, sizeof error), mj_deleteModel);
  if (!m) throw gaitopt::ConfigError(a.model, "", 0, std::string("MuJoCo: ") + error);
  std::unique_ptr<mjData, void (*)(mjData*)> d(mj_makeData(m.get()), mj_deleteData);
  const Robot robot = robotOf(m.get());
  const std::vector<Segment> segs = segmentsOf(traj.rows);
  setInitialState(robot, d.get(), traj.rows.front());

  const bool by_alpha = a.index == "alpha";
  std::vector<StepStats> steps;
  std::size_t seg = 0;
  double seg_t0 = 0.0;
  bool fell = false;
  const auto startStep = [&](int k) {
    StepStats s;
    s.step = k;
    s.t0 = d->time;
    s.foot0 = footOf(robot, d.get(), segs[seg].leg1());
    if (!steps.empty()) {
      steps.back().duration = s.t0 - steps.back().t0;
      steps.back().length = s.foot0(0) - steps.back().foot0(0);
      steps.back().speed = steps.back().length / steps.back().duration;
    }
    steps.push_back(s);
  };
  startStep(0);
  while (seg < segs.size()) {
    const Segment& sg = segs[seg];
    double alpha, alphad;
    tibiaAngle(robot, d.get(), sg.leg1(), alpha, alphad);
    const Reference ref =
        referenceAt(sg, by_alpha && (!a.ds_by_time || sg.rows.front().phase == Phase::SingleSupport),
                    alpha, alphad, sg.rows.front().t + d->time - seg_t0);
    if (ref.past_end) {
      seg_t0 = d->time;
      if (++seg < segs.size() && segs[seg].rows.front().phase == Phase::SingleSupport)
        startStep(segs[seg].rows.front().step);
      continue;
    }
    // A phase variable that stops progressing (the robot stalls or rocks back) is a failure.
    if (d->time - seg_t0 > 3.0 * (sg.rows.back().t - sg.rows.front().t) + 0.05) {
      std::fprintf(stderr, "stalled in step %d %s at t = %.3f s: alpha %.4f, segment ends at %.4f\n",
                   sg.rows.front().step, sg.rows.front().phase == Phase::SingleSupport ? "SS" : "DS",
                   d->time, alpha, sg.rows.back().alpha);
      fell = true;
      break;
    }
    StepStats& st = steps.back();
    for (int j = 0; j < 4; ++j) {
      const double e = ref.phi(j) - d->qpos[robot.qpos[j]];
      st.max_error = std::max(st.max_error, std::abs(e));
      d->ctrl[j] = ref.tau(j) + a.kp * e + a.kd * (ref.phid(j) - d->qvel[robot.dof[j]]);
    }
    if (sg.rows.front().phase == Phase::SingleSupport) {
      const Eigen::Vector2d f = footOf(robot, d.get(), sg.leg1());
      st.slip += std::abs(slipVelocity(robot, d.get(), sg.leg1())) * m->opt.timestep;
      st.lift = std::max(st.lift, f(1) - st.foot0(1));
    }
    mj_step(m.get(), d.get());
    if (fallen(d.get())) {
      fell = true;
      break;
    }
  }
  if (!fell) {  // the last step ends at the final lift-off: the front foot is the next stance
    seg = segs.size() - 1;
    const Eigen::Vector2d front = footOf(robot, d.get(), segs[seg].leg1());
    steps.back().duration = d->time - steps.back().t0;
    steps.back().length = front(0) - steps.back().foot0(0);
    steps.back().speed = steps.back().length / steps.back().duration;
  }

  std::printf("step  duration[s]  length[m]  speed[m/s]  max_err[rad]  slip[mm]  lift[mm]\n");
  double length = 0.0, time = 0.0;
  const StepStats* worst = nullptr;
  for (const StepStats& s : steps) {
    std::printf("%4d  %11.4f  %9.4f  %10.4f  %12.4f  %8.2f  %8.2f\n", s.step, s.duration,
                s.length, s.speed, s.max_error, 1e3 * s.slip, 1e3 * s.lift);
    length += s.length;
    time += s.duration;
    if (!worst || s.max_error > worst->max_error) worst = &s;
  }
  const double gait_speed = std::stod(traj.meta.at("speed_m_per_s"));
  const double mean = length / time;
  const int planned = traj.rows.back().step + 1;
  const bool ok = !fell && std::abs(mean / gait_speed - 1.0) <= a.speed_tolerance;
  std::printf("%s: %d/%d steps%s, mean speed %.4f m/s (gait %.4f, %+.2f %%), worst step %d "
              "(max tracking error %.4f rad), gains kp %g N*m/rad kd %g N*m*s/rad, index %s\n",
              ok ? "walked" : "FAILED", fell ? static_cast<int>(steps.size()) - 1 : planned,
              planned, fell ? " (fell)" : "", mean, gait_speed, 100 * (mean / gait_speed - 1),
              worst ? worst->step : -1, worst ? worst->max_error : 0.0, a.kp, a.kd,
              a.index.c_str());
  if (!a.steps_csv.empty()) gaitopt::writeFileAtomically(a.steps_csv, stepsTable(steps));
  return ok ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Play an exported gait on an exported MJCF robot in MuJoCo."};
  Args a;
  app.add_option("--model", a.model, "MJCF file (gaitopt export-model)")->required()
      ->check(CLI::ExistingFile);
  app.add_option("--trajectory", a.trajectory, "CSV file (gaitopt export)")->required()
      ->check(CLI::ExistingFile);
  app.add_option("--kp", a.kp, "PD stiffness [N*m/rad]")->capture_default_str();
  app.add_option("--kd", a.kd, "PD damping [N*m*s/rad]")->capture_default_str();
  app.add_option("--index", a.index, "Reference indexed by the phase variable or by time")
      ->capture_default_str()
      ->check(CLI::IsMember({"alpha", "time"}));
  app.add_flag("--ds-by-time", a.ds_by_time,
               "With --index alpha, index the double support by time from its start instead");
  app.add_option("--speed-tolerance", a.speed_tolerance, "Relative mean-speed tolerance")
      ->capture_default_str();
  app.add_option("--steps-csv", a.steps_csv, "Write the per-step table to this CSV file");
  try {
    app.parse(argc, argv);
    return run(a);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const gaitopt::ConfigError& e) {
    std::cerr << "mujoco_walk: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mujoco_walk: error: " << e.what() << "\n";
    return 2;
  }
}
