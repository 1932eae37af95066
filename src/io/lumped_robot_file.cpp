#include "gaitopt/io/lumped_robot_file.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace gaitopt {
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string mm(double metres) { return num(std::round(metres * 1e4) / 10.0) + " mm"; }

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : " + ") + n;
  return out;
}

// "tibia_r + talus_r 5.09 kg, CoM 0.262 m from the knee, 18.2 mm forward of the axis dropped"
std::string linkLine(const OsimLink& l, const char* from) {
  return joined(l.bodies) + ": " + num(l.mass) + " kg, length " + num(l.length) + " m, CoM " +
         num(l.com) + " m from the " + from + " (" + mm(std::abs(l.com_normal)) +
         (l.com_normal >= 0.0 ? " forward" : " behind") + " of the axis, dropped), I " + num(l.inertia) +
         " kg m^2";
}

}  // namespace

std::string lumpedRobotYaml(const OsimLumping& lumping, const std::string& name,
                            const std::string& model_path, const std::string& model_sha256) {
  const RobotParams& r = lumping.robot;
  std::ostringstream y;
  y << "# provenance: five-link lumping by gaitopt lump-osim of the OpenSim model\n"
    << "#   " << model_path << " (sha256 " << model_sha256 << "),\n"
    << "#   sagittal plane (x forward, y up), every coordinate at zero, masses summed, CoMs\n"
    << "#   mass-weighted, Izz about each CoM by the parallel-axis theorem.\n"
    << "#   - tibias (bodies 1, 5), knee to ankle; the point foot is the ankle joint centre:\n"
    << "#       right " << linkLine(lumping.tibia[0], "knee") << "\n"
    << "#       left  " << linkLine(lumping.tibia[1], "knee") << "\n"
    << "#   - femurs (bodies 2, 4), hip to knee:\n"
    << "#       right " << linkLine(lumping.femur[0], "hip") << "\n"
    << "#       left  " << linkLine(lumping.femur[1], "hip") << "\n"
    << "#   - trunk (body 3) = " << joined(lumping.trunk.bodies) << ": " << num(lumping.trunk.mass)
    << " kg,\n#     CoM " << num(lumping.trunk_com_up) << " m above and " << num(std::abs(lumping.trunk_com_forward))
    << (lumping.trunk_com_forward >= 0.0 ? " m ahead of" : " m behind") << " the hip midpoint; the trunk axis is the hip-CoM line, s3 = " << num(lumping.trunk.com)
    << " m,\n#     I " << num(lumping.trunk.inertia) << " kg m^2.\n"
    << "#   - left and right averaged; largest difference " << num(100.0 * lumping.asymmetry) << " % ("
    << lumping.asymmetry_quantity << ").\n"
    << "#   - dropped: CoM offsets off the link axes (above), out-of-plane offsets (largest "
    << mm(lumping.out_of_plane) << "\n#     between a leg's joint centres), the change of joint "
    << "centres with the joint angles.\n"
    << "#   - total " << num(lumping.model_mass) << " kg (every body of the model); gravity "
    << num(lumping.gravity) << " m/s^2 from the model;\n"
    << "#     no motors, no friction; joint_limits_deg: knees to 90 deg of flexion, hips +-75 deg\n"
    << "#     about the trunk (wide human ranges, for plots and import checks).\n"
    << "name: " << name << "\n"
    << "lengths: {l1: " << num(r.l1) << ", l2: " << num(r.l2) << ", l4: " << num(r.l4) << ", l5: " << num(r.l5) << "}\n";
  const auto five = [&](const char* key, const char* prefix, const std::array<double, 5>& v) {
    y << key << ": {";
    for (int i = 0; i < 5; ++i) y << (i ? ", " : "") << prefix << i + 1 << ": " << num(v[i]);
    y << "}\n";
  };
  five("com_offsets", "s", r.s);
  five("masses", "m", r.mass);
  five("inertias", "I", r.inertia);
  const double deg = 180.0 / M_PI;
  y << "joint_limits_deg: {hip_min: " << num(r.limits.hip_min * deg) << ", hip_max: " << num(r.limits.hip_max * deg)
    << ", knee_min: " << num(r.limits.knee_min * deg) << ", knee_max: " << num(r.limits.knee_max * deg) << "}\n"
    << "gravity: " << num(r.gravity) << "\n";
  if (const auto& f = lumping.pelvis_frame) {
    const auto pair = [](const std::array<double, 2>& v) { return "[" + num(v[0]) + ", " + num(v[1]) + "]"; };
    y << "pelvis_frame:  # the model's pelvis frame at zero angles, x forward, y up [m, kg]\n"
      << "  hip: " << pair(f->hip) << "\n  pelvis_com: " << pair(f->pelvis_com)
      << "\n  pelvis_mass: " << num(f->pelvis_mass) << "\n  back: " << pair(f->back)
      << "\n  torso_com: " << pair(f->torso_com) << "  # from the back joint, torso frame\n"
      << "  torso_mass: " << num(f->torso_mass) << "\n";
  }
  return y.str();
}

}  // namespace gaitopt
