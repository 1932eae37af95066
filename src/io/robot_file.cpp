#include "gaitopt/io/robot_file.hpp"

#include <cmath>

#include <algorithm>
#include <array>
#include <cstddef>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "gaitopt/model/support_bar.hpp"
#include "gaitopt/io/pelvis_frame_file.hpp"
#include "gaitopt/io/robot_extensions.hpp"
#include "gaitopt/io/yaml_reader.hpp"

namespace gaitopt {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadPerDeg = kPi / 180.0;

// Documented physical ranges of every robot number (docs/formats/robot-file.md and
// "Reliability"): wide enough for any RABBIT-class biped, narrow enough to refuse typos such as
// a mass of 1e300 or a denormal one, which would make every step undefined.
namespace ranges {
const Range kLength{1e-3, 10.0, false, "m"};
const Range kMass{1e-3, 1e3, false, "kg"};
const Range kInertia{1e-6, 1e3, false, "kg m^2"};
const Range kRotorInertia{0.0, 1.0, false, "kg m^2"};
const Range kGearRatio{1.0, 1e4, false, ""};
const Range kTorqueConstant{1e-4, 100.0, false, "N m/A"};
const Range kResistance{1e-4, 1e3, false, "ohm"};
const Range kCoulomb{0.0, 1e3, false, "N m"};
const Range kViscous{0.0, 1e3, false, "N m s/rad"};
const Range kEnvelopeSpeed{0.0, 1e4, false, "rad/s"};
const Range kEnvelopeTorque{0.0, 1e4, false, "N m"};
const Range kJointAngle{-720.0, 720.0, false, "deg"};
const Range kGravity{0.1, 100.0, false, "m/s^2"};
const Range kBarMass{0.0, 1e3, false, "kg"};
}  // namespace ranges

// One value per actuated joint (knee 1, hip 1, hip 2, knee 2).
std::array<double, 4> joints(const YamlMap& m, const std::string& key, const Range& range) {
  const std::vector<double> values = numbersIn(m, key, 4, range);
  std::array<double, 4> out{};
  std::copy(values.begin(), values.end(), out.begin());
  return out;
}

// Bodies C1..C5 stored under keys <letter>1..<letter>5 (m1..m5, s1..s5, I1..I5).
std::array<double, 5> bodies(const YamlMap& m, const std::string& letter, const Range& range) {
  std::array<double, 5> out{};
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = numberIn(m, letter + std::to_string(i + 1), range);
  }
  return out;
}

// Each CoM lies on its link (digest §1.3): s1, s5 from the knee along the tibias l1, l5; s2, s4
// from the hip along the femurs l2, l4; s3 from the hip along the trunk.
void requireComWithinLinks(const YamlMap& m, const RobotParams& robot) {
  const std::array<double, 5> link{robot.l1, robot.l2, robot.trunk_length, robot.l4, robot.l5};
  const std::array<const char*, 5> name{"l1", "l2", "trunk_length", "l4", "l5"};
  for (std::size_t i = 0; i < link.size(); ++i) {
    const std::string key = "s" + std::to_string(i + 1);
    if (robot.s[i] > link[i]) {
      throw m.error(key, "the centre of mass must lie within its link: " + m.text(key) +
                             " m > " + name[i] + " = " + showNumber(link[i]) + " m");
    }
  }
}

void readLengths(const YamlMap& m, RobotParams& robot) {
  robot.l1 = numberIn(m, "l1", ranges::kLength);
  robot.l2 = numberIn(m, "l2", ranges::kLength);
  robot.l4 = numberIn(m, "l4", ranges::kLength);
  robot.l5 = numberIn(m, "l5", ranges::kLength);
}

// Piecewise-linear envelope (3.47): breakpoints must be ordered for interpolation to work.
TorqueEnvelope readEnvelope(const YamlMap& m) {
  TorqueEnvelope envelope;
  const std::vector<double> speed =
      numbersIn(m, "speed", envelope.speed.size(), ranges::kEnvelopeSpeed);
  const std::vector<double> torque =
      numbersIn(m, "torque", envelope.torque.size(), ranges::kEnvelopeTorque);
  for (std::size_t k = 0; k < envelope.speed.size(); ++k) {
    if (k == 0 ? speed[k] < 0.0 : speed[k] <= speed[k - 1]) {
      throw m.elementError("speed", k, "speeds must be >= 0 and strictly increasing, got " +
                                           m.elementText("speed", k));
    }
    envelope.speed[k] = speed[k];
    envelope.torque[k] = torque[k];
  }
  return envelope;
}

void readMotors(const YamlMap& m, RobotParams& robot) {
  // 0 = lumped into the links
  robot.rotor_inertia = joints(m, "rotor_inertia", ranges::kRotorInertia);
  robot.gear_ratio = numberIn(m, "gear_ratio", ranges::kGearRatio);
  robot.motor_torque_constant = numberIn(m, "torque_constant", ranges::kTorqueConstant);
  robot.motor_resistance = numberIn(m, "resistance", ranges::kResistance);
  if (const auto envelope = m.optionalMap("envelope")) robot.envelope = readEnvelope(*envelope);
}

// Limits are written in degrees, as printed in (3.39), and stored in radians.
std::pair<double, double> degreeRange(const YamlMap& m, const std::string& min_key,
                                      const std::string& max_key) {
  const double lo = numberIn(m, min_key, ranges::kJointAngle);
  const double hi = numberIn(m, max_key, ranges::kJointAngle);
  if (lo >= hi) {
    throw m.error(min_key, "must be less than " + max_key + " (" + m.text(min_key) + " >= " +
                               m.text(max_key) + " deg)");
  }
  // Radians typed under a key in degrees: both bounds within ±2π and a range of a few units
  // is a joint that moves a few degrees, which no walking robot has.
  if (std::abs(lo) <= 2.0 * M_PI && std::abs(hi) <= 2.0 * M_PI && hi - lo < 2.0 * M_PI)
    throw m.error(min_key, "looks like radians (" + m.text(min_key) + " to " + m.text(max_key) +
                               "): joint_limits_deg holds degrees, e.g. -260 to -110 for a hip");
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
  bar.bar_length = numberIn(m, "bar_length", ranges::kLength);
  bar.overhang = numberIn(m, "overhang", ranges::kLength);
  bar.bar_mass = numberIn(m, "bar_mass", ranges::kMass);
  bar.counterweight_mass = numberIn(m, "counterweight_mass", ranges::kMass);
  if (bar.overhang >= bar.bar_length) {
    throw m.error("overhang", "must be shorter than bar_length (" + m.text("overhang") +
                                  " >= " + m.text("bar_length") + ")");
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
  bar.equivalent_mass = numberIn(m, "equivalent_mass", ranges::kBarMass);
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
  const YamlMap com_offsets = doc.map("com_offsets");
  robot.s = bodies(com_offsets, "s", Range{0.0, ranges::kLength.max, true, "m"});
  robot.mass = bodies(doc.map("masses"), "m", ranges::kMass);
  robot.inertia = bodies(doc.map("inertias"), "I", ranges::kInertia);
  // Without `motors` the joints are driven directly (a person, a direct-drive robot): no rotor
  // inertia enters (1.17); without `friction` the joints are frictionless (1.21).
  if (const auto motors = doc.optionalMap("motors")) readMotors(*motors, robot);
  if (const auto friction = doc.optionalMap("friction")) {
    robot.coulomb = joints(*friction, "coulomb", ranges::kCoulomb);
    robot.viscous = joints(*friction, "viscous", ranges::kViscous);
  }
  if (const auto limits = doc.optionalMap("joint_limits_deg")) {
    robot.limits = readJointLimits(*limits);
  }
  robot.gravity = numberInOr(doc, "gravity", ranges::kGravity, robot.gravity);
  if (const auto bar = doc.optionalMap("support_bar")) robot.bar = readSupportBar(*bar);
  robot.trunk_length = numberInOr(doc, "trunk_length", ranges::kLength, robot.trunk_length);
  requireComWithinLinks(com_offsets, robot);
  readRobotExtensions(doc, robot);
  readPelvisFrame(doc, robot.mass[2]);  // checked here, used by the OpenSim import
  doc.rejectUnknownKeys();
  return robot;
}

RobotParams loadRobot(const std::string& path) { return parseRobot(loadYamlFile(path), path); }

}  // namespace gaitopt
