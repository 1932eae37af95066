#include "gaitopt/io/robot_file.hpp"

#include <array>
#include <cstddef>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "gaitopt/model/support_bar.hpp"
#include "gaitopt/io/robot_extensions.hpp"
#include "gaitopt/io/yaml_reader.hpp"

namespace gaitopt {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadPerDeg = kPi / 180.0;

double positive(const YamlMap& m, const std::string& key) {
  const double value = m.number(key);
  if (value <= 0.0) throw m.error(key, "must be > 0, got " + showNumber(value));
  return value;
}

double nonNegative(const YamlMap& m, const std::string& key) {
  const double value = m.number(key);
  if (value < 0.0) throw m.error(key, "must be >= 0, got " + showNumber(value));
  return value;
}

double optionalPositive(const YamlMap& m, const std::string& key, double fallback) {
  return m.optionalNumber(key) ? positive(m, key) : fallback;
}

// One value per actuated joint (knee 1, hip 1, hip 2, knee 2), each >= 0.
std::array<double, 4> nonNegativeJoints(const YamlMap& m, const std::string& key) {
  const std::vector<double> values = m.numbers(key, 4);
  std::array<double, 4> joints{};
  for (std::size_t j = 0; j < joints.size(); ++j) {
    if (values[j] < 0.0) throw m.elementError(key, j, "must be >= 0, got " + showNumber(values[j]));
    joints[j] = values[j];
  }
  return joints;
}

// Bodies C1..C5 stored under keys <letter>1..<letter>5 (m1..m5, s1..s5, I1..I5), each > 0.
std::array<double, 5> positiveBodies(const YamlMap& m, const std::string& letter) {
  std::array<double, 5> bodies{};
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    bodies[i] = positive(m, letter + std::to_string(i + 1));
  }
  return bodies;
}

void readLengths(const YamlMap& m, RobotParams& robot) {
  robot.l1 = positive(m, "l1");
  robot.l2 = positive(m, "l2");
  robot.l4 = positive(m, "l4");
  robot.l5 = positive(m, "l5");
}

// Piecewise-linear envelope (3.47): breakpoints must be ordered for interpolation to work.
TorqueEnvelope readEnvelope(const YamlMap& m) {
  TorqueEnvelope envelope;
  const std::vector<double> speed = m.numbers("speed", envelope.speed.size());
  const std::vector<double> torque = m.numbers("torque", envelope.torque.size());
  for (std::size_t k = 0; k < envelope.speed.size(); ++k) {
    if (k == 0 ? speed[k] < 0.0 : speed[k] <= speed[k - 1]) {
      throw m.elementError("speed", k, "speeds must be >= 0 and strictly increasing, got " +
                                           showNumber(speed[k]));
    }
    if (torque[k] < 0.0)
      throw m.elementError("torque", k, "must be >= 0, got " + showNumber(torque[k]));
    envelope.speed[k] = speed[k];
    envelope.torque[k] = torque[k];
  }
  return envelope;
}

void readMotors(const YamlMap& m, RobotParams& robot) {
  robot.rotor_inertia = nonNegativeJoints(m, "rotor_inertia");  // 0 = lumped into the links
  robot.gear_ratio = positive(m, "gear_ratio");
  robot.motor_torque_constant = positive(m, "torque_constant");
  robot.motor_resistance = positive(m, "resistance");
  if (const auto envelope = m.optionalMap("envelope")) robot.envelope = readEnvelope(*envelope);
}

// Limits are written in degrees, as printed in (3.39), and stored in radians.
std::pair<double, double> degreeRange(const YamlMap& m, const std::string& min_key,
                                      const std::string& max_key) {
  const double lo = m.number(min_key);
  const double hi = m.number(max_key);
  if (lo >= hi) {
    throw m.error(min_key, "must be less than " + max_key + " (" + showNumber(lo) + " >= " +
                               showNumber(hi) + " deg)");
  }
  return {lo * kRadPerDeg, hi * kRadPerDeg};
}

JointLimits readJointLimits(const YamlMap& m) {
  JointLimits limits;
  std::tie(limits.hip_min, limits.hip_max) = degreeRange(m, "hip_min", "hip_max");
  std::tie(limits.knee_min, limits.knee_max) = degreeRange(m, "knee_min", "knee_max");
  return limits;
}

// Bar geometry (Fig. 1.9): equivalent hip mass by (1.29) with l_G = L_b/2.
SupportBar readBarGeometry(const YamlMap& bar_map, const YamlMap& m) {
  SupportBar bar;
  bar.present = true;
  bar.from_geometry = true;
  bar.bar_length = positive(m, "bar_length");
  bar.overhang = positive(m, "overhang");
  bar.bar_mass = positive(m, "bar_mass");
  bar.counterweight_mass = positive(m, "counterweight_mass");
  if (bar.overhang >= bar.bar_length) {
    throw m.error("overhang", "must be shorter than bar_length (" + showNumber(bar.overhang) +
                                  " >= " + showNumber(bar.bar_length) + ")");
  }
  bar.equivalent_mass =
      barEquivalentMass(bar.bar_length, bar.overhang, bar.bar_mass, bar.counterweight_mass);
  if (bar.equivalent_mass <= 0.0) {
    throw bar_map.error("geometry", "gives an equivalent mass (1.29) of " +
                                        showNumber(bar.equivalent_mass) +
                                        " kg <= 0: the counterweight outweighs the bar");
  }
  return bar;
}

// Either the equivalent point mass at the hip or the geometry it follows from (§1.4.2.4).
SupportBar readSupportBar(const YamlMap& m) {
  const std::optional<double> equivalent_mass = m.optionalNumber("equivalent_mass");
  const std::optional<YamlMap> geometry = m.optionalMap("geometry");
  if (equivalent_mass && geometry) {
    throw m.error("geometry", "give either equivalent_mass or geometry, not both");
  }
  if (geometry) return readBarGeometry(m, *geometry);
  if (!equivalent_mass) {
    throw m.error("equivalent_mass", "missing: give equivalent_mass or geometry");
  }
  SupportBar bar;
  bar.present = true;
  bar.equivalent_mass = nonNegative(m, "equivalent_mass");
  return bar;
}

}  // namespace

RobotParams parseRobot(const YAML::Node& root, const std::string& file) {
  const YamlMap doc(root, file, "");
  RobotParams robot;
  robot.source_file = file;
  robot.name = doc.string("name");
  if (robot.name.empty()) throw doc.error("name", "must not be empty");
  readLengths(doc.map("lengths"), robot);
  robot.s = positiveBodies(doc.map("com_offsets"), "s");
  robot.mass = positiveBodies(doc.map("masses"), "m");
  robot.inertia = positiveBodies(doc.map("inertias"), "I");
  // Without `motors` the joints are driven directly (a person, a direct-drive robot): no rotor
  // inertia enters (1.17); without `friction` the joints are frictionless (1.21).
  if (const auto motors = doc.optionalMap("motors")) readMotors(*motors, robot);
  if (const auto friction = doc.optionalMap("friction")) {
    robot.coulomb = nonNegativeJoints(*friction, "coulomb");
    robot.viscous = nonNegativeJoints(*friction, "viscous");
  }
  if (const auto limits = doc.optionalMap("joint_limits_deg")) {
    robot.limits = readJointLimits(*limits);
  }
  robot.gravity = optionalPositive(doc, "gravity", robot.gravity);
  if (const auto bar = doc.optionalMap("support_bar")) robot.bar = readSupportBar(*bar);
  robot.trunk_length = optionalPositive(doc, "trunk_length", robot.trunk_length);
  readRobotExtensions(doc, robot);
  doc.rejectUnknownKeys();
  return robot;
}

RobotParams loadRobot(const std::string& path) { return parseRobot(loadYamlFile(path), path); }

}  // namespace gaitopt
