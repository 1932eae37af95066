#include "gaitopt/io/robot_extensions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {

namespace {

void readJointMap(const YamlMap& parent, const std::string& key, std::array<double, 4>& values,
                  double* alpha = nullptr) {
  const std::optional<YamlMap> m = parent.optionalMap(key);
  if (!m) return;
  for (std::size_t j = 0; j < values.size(); ++j)
    if (const auto v = m->optionalNumber(kPhysicalJointNames[j])) values[j] = *v;
  if (alpha)
    if (const auto v = m->optionalNumber("alpha")) *alpha = *v;
}

void requirePositive(const YamlMap& parent, const std::string& key,
                     const std::array<double, 4>& values) {
  for (std::size_t j = 0; j < values.size(); ++j)
    if (!(values[j] > 0.0))
      throw parent.map(key).error(kPhysicalJointNames[j],
                                  "must be > 0, got " + showNumber(values[j]));
}

void writeJointMap(std::ostringstream& out, const char* key, const std::array<double, 4>& values,
                   double neutral, const double* alpha = nullptr) {
  std::string body;
  for (std::size_t j = 0; j < values.size(); ++j)
    if (values[j] != neutral)
      body += (body.empty() ? "" : ", ") + std::string(kPhysicalJointNames[j]) + ": " +
              formatDouble(values[j]);
  if (alpha && *alpha != 0.0) body += (body.empty() ? "alpha: " : ", alpha: ") + formatDouble(*alpha);
  if (!body.empty()) out << "  " << key << ": {" << body << "}\n";
}

}  // namespace

void readRobotExtensions(const YamlMap& doc, RobotParams& robot) {
  if (const auto j = doc.optionalMap("joint_extras")) {
    readJointMap(*j, "coulomb", robot.joint_extras.coulomb);
    readJointMap(*j, "viscous", robot.joint_extras.viscous);
    readJointMap(*j, "rotor_inertia_factor", robot.joint_extras.rotor_inertia_factor);
    if (j->hasMapping("rotor_inertia_factor"))
      requirePositive(*j, "rotor_inertia_factor", robot.joint_extras.rotor_inertia_factor);
  }
  if (const auto s = doc.optionalMap("sensors")) {
    SensorModel& m = robot.sensors;
    readJointMap(*s, "torque_gain", m.torque_gain);
    if (s->hasMapping("torque_gain")) requirePositive(*s, "torque_gain", m.torque_gain);
    readJointMap(*s, "torque_offset", m.torque_offset);
    readJointMap(*s, "encoder_offset", m.encoder_offset, &m.alpha_offset);
    readJointMap(*s, "backlash", m.backlash);
  }
  robot.hip_payload = doc.optionalNumber("hip_payload").value_or(0.0);
  robot.trunk_com_shift = doc.optionalNumber("trunk_com_shift").value_or(0.0);
  robot.ground_slope = doc.optionalNumber("ground_slope").value_or(0.0);
  if (std::abs(robot.ground_slope) >= 0.5)
    throw doc.error("ground_slope", "must be within ±0.5 rad, got " + showNumber(robot.ground_slope));
  // An effective rocker (roll-over shape) may be centred above the knee, not above the hip.
  const double leg = std::min(robot.l1 + robot.l2, robot.l4 + robot.l5);
  robot.foot_radius = doc.optionalNumber("foot_radius").value_or(0.0);
  if (!(robot.foot_radius >= 0.0 && robot.foot_radius < leg))
    throw doc.error("foot_radius", "must be >= 0 and below the leg length " + showNumber(leg) +
                                       " m, got " + showNumber(robot.foot_radius));
  robot.foot_offset = doc.optionalNumber("foot_offset").value_or(0.0);
  if (!(std::abs(robot.foot_offset) < leg))
    throw doc.error("foot_offset", "must be within ± the leg length " + showNumber(leg) +
                                       " m, got " + showNumber(robot.foot_offset));
}

std::string robotExtensionsYaml(const RobotParams& robot) {
  std::ostringstream out;
  std::ostringstream joints;
  writeJointMap(joints, "coulomb", robot.joint_extras.coulomb, 0.0);
  writeJointMap(joints, "viscous", robot.joint_extras.viscous, 0.0);
  writeJointMap(joints, "rotor_inertia_factor", robot.joint_extras.rotor_inertia_factor, 1.0);
  if (!joints.str().empty()) out << "joint_extras:\n" << joints.str();
  std::ostringstream sensors;
  const SensorModel& m = robot.sensors;
  writeJointMap(sensors, "torque_gain", m.torque_gain, 1.0);
  writeJointMap(sensors, "torque_offset", m.torque_offset, 0.0);
  writeJointMap(sensors, "encoder_offset", m.encoder_offset, 0.0, &m.alpha_offset);
  writeJointMap(sensors, "backlash", m.backlash, 0.0);
  if (!sensors.str().empty()) out << "sensors:\n" << sensors.str();
  if (robot.hip_payload != 0.0) out << "hip_payload: " << formatDouble(robot.hip_payload) << "\n";
  if (robot.trunk_com_shift != 0.0)
    out << "trunk_com_shift: " << formatDouble(robot.trunk_com_shift) << "\n";
  if (robot.ground_slope != 0.0) out << "ground_slope: " << formatDouble(robot.ground_slope) << "\n";
  if (robot.foot_radius != 0.0) out << "foot_radius: " << formatDouble(robot.foot_radius) << "\n";
  if (robot.foot_offset != 0.0) out << "foot_offset: " << formatDouble(robot.foot_offset) << "\n";
  return out.str();
}

}  // namespace gaitopt
