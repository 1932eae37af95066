#include "gaitopt/export/robot_export.hpp"

#include <cmath>
#include <sstream>

#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {
namespace {

std::string num(double v) { return formatDouble(v); }

std::string vec3(double x, double y, double z) { return num(x) + " " + num(y) + " " + num(z); }

// Bodies and joints shared by both formats, in the reference pose (upright trunk, straight
// vertical legs), lengths along the body's pointing direction.
struct LegGeometry {
  std::string side;
  double femur, femur_com, femur_mass, femur_inertia;
  double tibia, tibia_com, tibia_mass, tibia_inertia;
  double hip_rotor, knee_rotor, hip_coulomb, knee_coulomb, hip_viscous, knee_viscous;
};

struct TreeGeometry {
  double trunk_com_shift;  // bar-less trunk CoM above the trunk-with-bar CoM
  double hip_depth;        // hip below the trunk-with-bar CoM (s3*)
  double trunk_mass, trunk_inertia, bar_mass, trunk_length;
  LegGeometry legs[2];
  double hip_min, hip_max, knee_min, knee_max;  // on φ
  double armature_scale;                       // N²
  double gravity;
};

TreeGeometry treeGeometry(const RobotParams& r) {
  const Model m = buildModel(r);
  TreeGeometry g;
  g.hip_depth = m.com_offset(2);
  g.trunk_com_shift = r.s[2] - m.com_offset(2);
  g.trunk_mass = r.mass[2];
  g.trunk_inertia = r.inertia[2];
  g.bar_mass = r.bar.present ? r.bar.equivalent_mass : 0.0;
  g.trunk_length = r.trunk_length;
  // Leg 1 (bodies 1, 2; knee 1 = joint 0, hip 1 = joint 1) is the left leg.
  g.legs[0] = {"left",        r.l2, r.s[1], r.mass[1], r.inertia[1], r.l1, r.s[0], r.mass[0],
               r.inertia[0], r.rotor_inertia[1], r.rotor_inertia[0], r.coulomb[1],
               r.coulomb[0], r.viscous[1], r.viscous[0]};
  g.legs[1] = {"right",       r.l4, r.s[3], r.mass[3], r.inertia[3], r.l5, r.s[4], r.mass[4],
               r.inertia[4], r.rotor_inertia[2], r.rotor_inertia[3], r.coulomb[2],
               r.coulomb[3], r.viscous[2], r.viscous[3]};
  // (3.39) on δ2, δ2 + δ3 and δ1, δ4; the hip motor angle is −δ2 (or −(δ2 + δ3)).
  g.hip_min = -r.limits.hip_max;
  g.hip_max = -r.limits.hip_min;
  g.knee_min = r.limits.knee_min;
  g.knee_max = r.limits.knee_max;
  g.armature_scale = r.gear_ratio * r.gear_ratio;
  g.gravity = r.gravity;
  return g;
}

double maxTorque(const RobotParams& r) {
  double t = 0.0;
  for (double v : r.envelope.torque) t = std::max(t, v);
  return t;
}

void mjcfInertial(std::ostringstream& o, const std::string& indent, double z, double mass,
                  double inertia) {
  o << indent << "<inertial pos=\"" << vec3(0, 0, z) << "\" mass=\"" << num(mass)
    << "\" diaginertia=\"" << vec3(inertia, inertia, inertia) << "\"/>\n";
}

void mjcfJoint(std::ostringstream& o, const std::string& indent, const std::string& name,
               double ref, double lo, double hi, double rotor, double armature_scale,
               double coulomb, double viscous) {
  o << indent << "<joint name=\"" << name << "\" type=\"hinge\" axis=\"0 1 0\" ref=\""
    << num(ref) << "\" limited=\"true\" range=\"" << num(lo) << " " << num(hi)
    << "\" armature=\"" << num(rotor * armature_scale) << "\" damping=\"" << num(viscous)
    << "\" frictionloss=\"" << num(coulomb) << "\"/>\n";
}

void mjcfLeg(std::ostringstream& o, const TreeGeometry& g, const LegGeometry& l,
             const ModelExportOptions& opt) {
  const std::string i2 = "      ", i3 = "        ", i4 = "          ";
  o << i2 << "<body name=\"femur_" << l.side << "\" pos=\"" << vec3(0, 0, -g.hip_depth)
    << "\">\n";
  // Reference pose: femur straight down from the upright trunk, φ_hip = π.
  mjcfJoint(o, i3, "hip_" + l.side, M_PI, g.hip_min, g.hip_max, l.hip_rotor, g.armature_scale,
            l.hip_coulomb, l.hip_viscous);
  mjcfInertial(o, i3, -l.femur_com, l.femur_mass, l.femur_inertia);
  o << i3 << "<geom type=\"capsule\" fromto=\"0 0 0 0 0 " << num(-l.femur)
    << "\" size=\"0.02\" contype=\"0\" conaffinity=\"0\" rgba=\"0.3 0.5 0.8 1\"/>\n";
  o << i3 << "<body name=\"tibia_" << l.side << "\" pos=\"" << vec3(0, 0, -l.femur) << "\">\n";
  // Straight knee: δ = −π.
  mjcfJoint(o, i4, "knee_" + l.side, -M_PI, g.knee_min, g.knee_max, l.knee_rotor,
            g.armature_scale, l.knee_coulomb, l.knee_viscous);
  mjcfInertial(o, i4, -l.tibia_com, l.tibia_mass, l.tibia_inertia);
  o << i4 << "<geom type=\"capsule\" fromto=\"0 0 0 0 0 " << num(-l.tibia)
    << "\" size=\"0.015\" contype=\"0\" conaffinity=\"0\" rgba=\"0.3 0.5 0.8 1\"/>\n";
  o << i4 << "<geom name=\"foot_" << l.side << "\" type=\"sphere\" pos=\"" << vec3(0, 0, -l.tibia)
    << "\" size=\"" << num(opt.foot_radius)
    << "\" contype=\"2\" conaffinity=\"1\" condim=\"3\" rgba=\"0.8 0.3 0.3 1\"/>\n";
  o << i4 << "<site name=\"foot_" << l.side << "\" pos=\"" << vec3(0, 0, -l.tibia)
    << "\" size=\"0.005\"/>\n";
  o << i3 << "</body>\n" << i2 << "</body>\n";
}

}  // namespace

std::string robotMjcf(const RobotParams& r, const ModelExportOptions& opt) {
  const TreeGeometry g = treeGeometry(r);
  const double stand = g.legs[0].tibia + g.legs[0].femur + g.hip_depth;
  std::ostringstream o;
  o << "<!-- " << r.name << ": written by gaitopt export-model from " << r.source_file
    << ". Planar (x-z) model; joint values are the joint-side motor angles phi (rad), "
       "armature = rotor inertia * N^2 (high-gear approximation). -->\n";
  o << "<mujoco model=\"" << r.name << "\">\n";
  o << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
  o << "  <option timestep=\"" << num(opt.timestep) << "\" gravity=\"0 0 " << num(-g.gravity)
    << "\" integrator=\"Euler\"/>\n";
  o << "  <default><geom solref=\"0.004 1\"/></default>\n";
  o << "  <worldbody>\n";
  o << "    <geom name=\"floor\" type=\"plane\" size=\"0 0 0.1\" pos=\"0 0 "
    << num(-opt.foot_radius) << "\" contype=\"1\" conaffinity=\"2\" condim=\"3\" friction=\""
    << num(opt.ground_friction) << " 0.005 0.0001\"/>\n";
  o << "    <body name=\"trunk\" pos=\"" << vec3(0, 0, stand) << "\">\n";
  o << "      <joint name=\"rootx\" type=\"slide\" axis=\"1 0 0\" ref=\"0\"/>\n";
  o << "      <joint name=\"rootz\" type=\"slide\" axis=\"0 0 1\" ref=\"" << num(stand)
    << "\"/>\n";
  o << "      <joint name=\"rooty\" type=\"hinge\" axis=\"0 -1 0\" ref=\"0\"/>\n";
  mjcfInertial(o, "      ", g.trunk_com_shift, g.trunk_mass, g.trunk_inertia);
  o << "      <geom type=\"capsule\" fromto=\"0 0 " << num(-g.hip_depth) << " 0 0 "
    << num(g.trunk_length - g.hip_depth)
    << "\" size=\"0.04\" contype=\"0\" conaffinity=\"0\" rgba=\"0.6 0.6 0.6 1\"/>\n";
  if (g.bar_mass > 0.0) {
    o << "      <body name=\"support_bar\" pos=\"" << vec3(0, 0, -g.hip_depth) << "\">\n";
    o << "        <inertial pos=\"0 0 0\" mass=\"" << num(g.bar_mass)
      << "\" diaginertia=\"0 0 0\"/>\n";
    o << "      </body>\n";
  }
  for (const LegGeometry& l : g.legs) mjcfLeg(o, g, l, opt);
  o << "    </body>\n  </worldbody>\n  <actuator>\n";
  const double t = maxTorque(r);
  for (const char* j : {"knee_left", "hip_left", "hip_right", "knee_right"})
    o << "    <motor name=\"" << j << "\" joint=\"" << j << "\" gear=\"1\" ctrllimited=\"true\" "
      << "ctrlrange=\"" << num(-t) << " " << num(t) << "\"/>\n";
  o << "  </actuator>\n</mujoco>\n";
  return o.str();
}

namespace {

void urdfLink(std::ostringstream& o, const std::string& name, double z, double mass,
              double inertia, const std::string& visual) {
  o << "  <link name=\"" << name << "\">\n    <inertial>\n      <origin xyz=\"" << vec3(0, 0, z)
    << "\" rpy=\"0 0 0\"/>\n      <mass value=\"" << num(mass) << "\"/>\n      <inertia ixx=\""
    << num(inertia) << "\" ixy=\"0\" ixz=\"0\" iyy=\"" << num(inertia) << "\" iyz=\"0\" izz=\""
    << num(inertia) << "\"/>\n    </inertial>\n" << visual << "  </link>\n";
}

std::string urdfCylinder(double length, double radius) {
  return "    <visual>\n      <origin xyz=\"" + vec3(0, 0, 0.5 * length) +
         "\" rpy=\"0 0 0\"/>\n      <geometry><cylinder radius=\"" + num(radius) +
         "\" length=\"" + num(std::abs(length)) + "\"/></geometry>\n    </visual>\n";
}

void urdfRevolute(std::ostringstream& o, const std::string& name, const std::string& parent,
                  const std::string& child, double z, double pitch, double lo, double hi,
                  double effort, double coulomb, double viscous) {
  o << "  <joint name=\"" << name << "\" type=\"revolute\">\n    <parent link=\"" << parent
    << "\"/>\n    <child link=\"" << child << "\"/>\n    <origin xyz=\"" << vec3(0, 0, z)
    << "\" rpy=\"" << vec3(0, pitch, 0) << "\"/>\n    <axis xyz=\"0 1 0\"/>\n    <limit lower=\""
    << num(lo) << "\" upper=\"" << num(hi) << "\" effort=\"" << num(effort)
    << "\" velocity=\"100\"/>\n    <dynamics damping=\"" << num(viscous) << "\" friction=\""
    << num(coulomb) << "\"/>\n  </joint>\n";
}

}  // namespace

// Link frames: at joint value 0 every link is oriented like the trunk, and each leg link
// extends along its local +z; a rotation φ about +y turns it by −φ in the x–z plane, so
// φ_hip = π hangs the femur down and the knee's extra half-turn (rpy 0 π 0) makes δ = −π
// straight.
std::string robotUrdf(const RobotParams& r, const ModelExportOptions& opt) {
  const TreeGeometry g = treeGeometry(r);
  const double effort = maxTorque(r);
  std::ostringstream o;
  o << "<?xml version=\"1.0\"?>\n<!-- " << r.name << ": written by gaitopt export-model from "
    << r.source_file
    << ". Planar model in the x-z plane; joint values are the joint-side motor angles phi "
       "(rad); rotor inertias (motor side) "
    << num(r.rotor_inertia[0]) << ", " << num(r.rotor_inertia[1]) << ", "
    << num(r.rotor_inertia[2]) << ", " << num(r.rotor_inertia[3]) << " kg m^2 for knee_left, "
    << "hip_left, hip_right, knee_right, gear ratio " << num(r.gear_ratio)
    << " (URDF has no armature). -->\n";
  o << "<robot name=\"" << r.name << "\">\n  <link name=\"world\"/>\n";
  urdfLink(o, "trunk", g.trunk_com_shift, g.trunk_mass, g.trunk_inertia,
           "    <visual>\n      <origin xyz=\"" + vec3(0, 0, 0.5 * g.trunk_length - g.hip_depth) +
               "\" rpy=\"0 0 0\"/>\n      <geometry><box size=\"0.08 0.08 " +
               num(g.trunk_length) + "\"/></geometry>\n    </visual>\n");
  o << "  <joint name=\"root\" type=\"planar\">\n    <parent link=\"world\"/>\n    <child "
       "link=\"trunk\"/>\n    <origin xyz=\"0 0 0\" rpy=\"0 0 0\"/>\n    <axis xyz=\"0 1 0\"/>\n"
       "  </joint>\n";
  if (g.bar_mass > 0.0) {
    urdfLink(o, "support_bar", 0.0, g.bar_mass, 0.0, "");
    o << "  <joint name=\"support_bar\" type=\"fixed\">\n    <parent link=\"trunk\"/>\n    "
         "<child link=\"support_bar\"/>\n    <origin xyz=\""
      << vec3(0, 0, -g.hip_depth) << "\" rpy=\"0 0 0\"/>\n  </joint>\n";
  }
  for (const LegGeometry& l : g.legs) {
    urdfLink(o, "femur_" + l.side, l.femur_com, l.femur_mass, l.femur_inertia,
             urdfCylinder(l.femur, 0.02));
    urdfRevolute(o, "hip_" + l.side, "trunk", "femur_" + l.side, -g.hip_depth, 0.0, g.hip_min,
                 g.hip_max, effort, l.hip_coulomb, l.hip_viscous);
    urdfLink(o, "tibia_" + l.side, l.tibia_com, l.tibia_mass, l.tibia_inertia,
             urdfCylinder(l.tibia, 0.015) + "    <collision>\n      <origin xyz=\"" +
                 vec3(0, 0, l.tibia) + "\" rpy=\"0 0 0\"/>\n      <geometry><sphere radius=\"" +
                 num(opt.foot_radius) + "\"/></geometry>\n    </collision>\n");
    urdfRevolute(o, "knee_" + l.side, "femur_" + l.side, "tibia_" + l.side, l.femur, M_PI,
                 g.knee_min, g.knee_max, effort, l.knee_coulomb, l.knee_viscous);
  }
  o << "</robot>\n";
  return o.str();
}

Eigen::Matrix<double, 7, 7> mjcfCoordinateMap() {
  Eigen::Matrix<double, 7, 7> L;
  // columns: α, δ1, δ2, δ3, δ4, x_t, z_t
  L << 0, 0, 0, 0, 0, 1, 0,  // rootx
      0, 0, 0, 0, 0, 0, 1,   // rootz
      1, 1, -1, 0, 0, 0, 0,  // rooty = θ3 − π/2 (1.13)
      0, 0, -1, 0, 0, 0, 0,  // hip_left = −δ2
      0, 1, 0, 0, 0, 0, 0,   // knee_left = δ1
      0, 0, -1, -1, 0, 0, 0, // hip_right = −(δ2 + δ3)
      0, 0, 0, 0, 1, 0, 0;   // knee_right = δ4
  return L;
}

}  // namespace gaitopt
