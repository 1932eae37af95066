// Validates the reference walking controller (C interface gaitopt/control/walker.h, library
// libgaitopt_walker) on an exported MJCF robot (gaitopt export-model) in MuJoCo: floating
// base, soft contacts with friction, the robot file's joint friction and rotor inertia in the
// plant (mujoco_walk_sim.hpp). The controller sees only what a robot's sensors give: the hip,
// the trunk pitch, the joint angles, their rates and two foot contact flags. One summary line
// is printed; exit 0 when every step was walked and the last half's mean speed is within 5 %
// of the gait's, 3 otherwise, 2 on bad input.
//
//   mujoco_walk --model rabbit.xml --export gait.json [--steps 100] [--rate 1000]
//               [--velocity-scale F] [--trunk-mass-scale F] [--slope RAD] [--push DV]
//               [--gain-scale G | --options YAML] [--steps-csv FILE] [--summary-csv FILE]
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "gaitopt/control/walker.h"
#include "mujoco_walk_sim.hpp"

namespace {

using namespace mujoco_walk;

struct Args {
  WalkOptions walk;
  std::string export_path, options, steps_csv, summary_csv;
  std::optional<double> gain_scale;
};

// A file replaced in one rename, so a reader never sees it half written.
void writeAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out.flush()) throw BadInput(path + ": cannot write");
  }
  std::filesystem::rename(tmp, path);
}

std::string stepsTable(const std::vector<StepStats>& steps) {
  std::ostringstream o;
  o.precision(10);
  o << "step,stance,t_start,foot_x,foot_z,duration,length,speed,stance_slip\n";
  for (const StepStats& s : steps)
    o << s.step << ',' << kSides[s.stance] << ',' << s.t0 << ',' << s.foot_x << ',' << s.foot_z
      << ',' << s.duration << ',' << s.length << ',' << s.speed << ',' << s.slip << '\n';
  return o.str();
}

std::string summaryCsv(const Summary& s, double t_end) {
  char line[256];
  std::snprintf(line, sizeof line, "%d,%d,%.6f,%.4f,%.4f,%s,%.4f\n", s.walked ? 1 : 0, s.steps,
                s.mean_speed, s.speed_error, 1e3 * s.max_slip,
                s.reason.empty() ? "ok" : s.reason.c_str(), t_end);
  return std::string("walked,steps,mean_speed_last_half,speed_error_percent,max_slip_mm,reason,"
                     "t_end\n") + line;
}

void printState(const char* what, const gaitopt_walker_state& s) {
  std::fprintf(stderr,
               "%s at t = %.4f s: hip (%.4f, %.4f) m, pitch %.4f rad, phi (%.3f, %.3f, %.3f, "
               "%.3f) rad, xd_hip %.3f m/s, pitchd %.3f rad/s, contact (%d, %d)\n",
               what, s.t, s.x_hip, s.z_hip, s.pitch, s.phi[0], s.phi[1], s.phi[2], s.phi[3],
               s.xd_hip, s.pitchd, s.contact[0], s.contact[1]);
}

int run(const Args& a) {
  std::string options = a.options;
  if (a.gain_scale) {
    std::ostringstream o;
    o.precision(17);
    o << "gain_scale: " << *a.gain_scale;
    options = o.str();
  }
  const WalkerPtr walker = loadWalker(a.export_path, options);
  const Outcome out = walkInMujoco(a.walk, walker.get());
  const double speed = gaitopt_walker_speed(walker.get());
  const Summary sum = summarise(out, a.walk.steps, speed);
  if (!sum.walked && sum.reason != "speed_error") printState(sum.reason.c_str(), out.last);
  std::printf("%s: %d/%d steps, mean speed of the last half %.4f m/s (gait %.4f, %+.2f %%), "
              "max stance slip %.2f mm, t %.3f s%s%s\n",
              sum.walked ? "walked" : "FAILED", sum.steps, a.walk.steps, sum.mean_speed, speed,
              sum.speed_error, 1e3 * sum.max_slip, out.t_end, sum.reason.empty() ? "" : ", ",
              sum.reason.c_str());
  if (!a.steps_csv.empty()) writeAtomically(a.steps_csv, stepsTable(out.steps));
  if (!a.summary_csv.empty()) writeAtomically(a.summary_csv, summaryCsv(sum, out.t_end));
  return sum.walked ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Walk the reference controller (libgaitopt_walker, C interface) on an exported MJCF "
      "robot in MuJoCo; optionally perturbed. Exit 0 when every step was walked and the last "
      "half's mean speed is within 5 % of the gait's, 3 otherwise, 2 on bad input."};
  Args a;
  app.add_option("--model", a.walk.model, "MJCF file (gaitopt export-model --format mjcf)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--export", a.export_path,
                 "Gait file of the controller (gaitopt export --format json)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--steps", a.walk.steps, "Steps to walk")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  app.add_option("--rate", a.walk.rate, "Controller call rate [Hz], torques held between calls")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1e6));
  app.add_option("--velocity-scale", a.walk.velocity_scale,
                 "Perturbation: every initial velocity times F (the stance foot stays at rest)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--trunk-mass-scale", a.walk.trunk_mass_scale,
                 "Perturbation: the plant's trunk mass and inertia times F (the controller "
                 "keeps its model)")
      ->capture_default_str()
      ->check(CLI::Range(0.1, 10.0));
  app.add_option("--slope", a.walk.slope,
                 "Perturbation: floor rotated by RAD about y through the first stance foot, "
                 "+ uphill toward +x; gravity vertical")
      ->capture_default_str()
      ->check(CLI::Range(-0.5, 0.5));
  app.add_option("--push", a.walk.push,
                 "Perturbation: horizontal impulse of total mass x DV [m/s] on the trunk, a "
                 "constant force over 0.02 s from mid single support of step steps/5")
      ->capture_default_str()
      ->check(CLI::Range(-10.0, 10.0));
  CLI::Option* gain = app.add_option("--gain-scale", a.gain_scale,
                                     "Controller option gain_scale (PD gains times G)")
                          ->check(CLI::Range(1e-3, 1e3));
  app.add_option("--options", a.options, "Controller options as a YAML mapping (walker.h)")
      ->excludes(gain);
  app.add_option("--steps-csv", a.steps_csv, "Write the per-step table to this CSV file");
  app.add_option("--summary-csv", a.summary_csv, "Write the summary as a one-row CSV file");
  try {
    app.parse(argc, argv);
    return run(a);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const std::exception& e) {  // BadInput, or a file that cannot be written
    std::cerr << "mujoco_walk: error: " << e.what() << "\n";
    return 2;
  }
}
