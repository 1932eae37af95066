#include "gaitopt/ident/effects.hpp"

#include <cmath>
#include <stdexcept>

namespace gaitopt {

namespace {

constexpr std::array<EffectInfo, kNumEffectKinds> kEffects = {{
    {"coulomb", "N·m", true, false, true, 1.0, true},
    {"viscous", "N·m·s/rad", true, false, true, 1.0, true},
    {"rotor_inertia", "factor", true, true, true, 0.1, true},
    {"torque_offset", "N·m", true, false, true, 1.0, true},
    {"torque_gain", "factor", true, true, true, 0.01, true},
    {"encoder_offset", "rad", true, false, false, 1e-3, false},
    {"backlash", "rad", true, false, true, 1e-3, false},
    {"payload", "kg", false, false, false, 0.5, false},
    {"trunk_com", "m", false, false, false, 5e-3, false},
    {"slope", "rad", false, false, false, 1e-3, false},
    {"rocker_foot", "m", false, false, false, 1e-2, false},
    {"foot_offset", "m", false, false, false, 5e-3, false},
    {"inertial", "", false, false, false, 1.0, true},
}};

// Width of the smoothed sign of the backlash dead band [N·m]: about 1 N·m.
constexpr double kBacklashTorqueWidth = 1.0;

}  // namespace

const EffectInfo& effectInfo(EffectKind kind) { return kEffects[static_cast<int>(kind)]; }

std::string jointName(int joint) {
  if (joint == kAlphaJoint) return "alpha";
  if (joint < 0) return "";
  return kPhysicalJointNames[joint];
}

std::string effectLabel(const Effect& e) {
  const std::string j = jointName(e.joint);
  return std::string(effectInfo(e.kind).name) + (j.empty() ? "" : "@" + j);
}

double parseEffectValue(const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value))
    throw std::invalid_argument("value '" + text + "' is not a number");
  return value;
}

Effect parseEffectSpec(const std::string& spec) {
  const std::size_t eq = spec.find('=');
  if (eq == std::string::npos) throw std::invalid_argument("expected NAME[@JOINT]=VALUE");
  const std::string head = spec.substr(0, eq);
  const std::size_t at = head.find('@');
  const std::string name = head.substr(0, at);
  Effect e{EffectKind::Coulomb};
  bool found = false;
  for (int k = 0; k < kNumEffectKinds; ++k)
    if (name == kEffects[k].name) {
      e.kind = static_cast<EffectKind>(k);
      found = true;
    }
  if (!found) throw std::invalid_argument("unknown effect '" + name + "'");
  if (e.kind == EffectKind::Inertial)
    throw std::invalid_argument("inertial has no single value: change the robot file's masses, "
                                "com_offsets and inertias instead");
  const EffectInfo& info = effectInfo(e.kind);
  if (info.per_joint) {
    if (at == std::string::npos) throw std::invalid_argument(name + " needs @JOINT");
    const std::string joint = head.substr(at + 1);
    for (int j = 0; j <= kAlphaJoint; ++j)
      if (joint == jointName(j)) e.joint = j;
    if (e.joint < 0 || (e.joint == kAlphaJoint && e.kind != EffectKind::EncoderOffset))
      throw std::invalid_argument("unknown joint '" + joint + "' for " + name);
  } else if (at != std::string::npos) {
    throw std::invalid_argument(name + " takes no joint");
  }
  e.value = parseEffectValue(spec.substr(eq + 1));
  if (info.factor && e.value <= 0.0) throw std::invalid_argument(name + " must be > 0");
  return e;
}

RobotParams withEffect(RobotParams r, const Effect& e) {
  const int j = e.joint;
  switch (e.kind) {
    case EffectKind::Coulomb: r.joint_extras.coulomb[j] += e.value; break;
    case EffectKind::Viscous: r.joint_extras.viscous[j] += e.value; break;
    case EffectKind::RotorInertia: r.joint_extras.rotor_inertia_factor[j] *= e.value; break;
    case EffectKind::TorqueOffset: r.sensors.torque_offset[j] += e.value; break;
    case EffectKind::TorqueGain: r.sensors.torque_gain[j] *= e.value; break;
    case EffectKind::EncoderOffset:
      (j == kAlphaJoint ? r.sensors.alpha_offset : r.sensors.encoder_offset[j]) += e.value;
      break;
    case EffectKind::Backlash: r.sensors.backlash[j] += e.value; break;
    case EffectKind::Payload: r.hip_payload += e.value; break;
    case EffectKind::TrunkCom: r.trunk_com_shift += e.value; break;
    case EffectKind::Slope: r.ground_slope += e.value; break;
    case EffectKind::RockerFoot: r.foot_radius += e.value; break;
    case EffectKind::FootOffset: r.foot_offset += e.value; break;
    case EffectKind::Inertial: break;  // many parameters: withInertialChange
  }
  return r;
}

RobotParams withEffects(RobotParams robot, const std::vector<Effect>& effects) {
  for (const Effect& e : effects) robot = withEffect(robot, e);
  return robot;
}

RobotParams stanceRobot(const RobotParams& robot, Stance stance) {
  RobotParams r = robot;
  for (int j = 0; j < 4; ++j) {
    const int p = physicalJointOfMotor(j, stance);
    r.coulomb[j] += robot.joint_extras.coulomb[p];
    r.viscous[j] += robot.joint_extras.viscous[p];
    r.rotor_inertia[j] *= robot.joint_extras.rotor_inertia_factor[p];
  }
  r.joint_extras = JointExtras{};
  return r;
}

Vec4 motorAngles(const Vec5& q) { return Vec4(q(1), -q(2), -(q(2) + q(3)), q(4)); }

Vec5 qFromMotorAngles(double alpha, const Vec4& m) {
  return Vec5(alpha, m(0), -m(1), m(1) - m(2), m(3));
}

Vec4 backlashShift(const SensorModel& s, Stance stance, const Vec4& gamma_star) {
  Vec4 shift;
  for (int j = 0; j < 4; ++j)
    shift(j) = 0.5 * s.backlash[physicalJointOfMotor(j, stance)] *
               std::tanh(gamma_star(j) / kBacklashTorqueWidth);
  return shift;
}

SensorReading sensorReading(const SensorModel& s, Stance stance, const Vec5& q,
                            const Vec4& gamma_star) {
  Vec4 motor = motorAngles(q) + backlashShift(s, stance, gamma_star);
  SensorReading r;
  for (int j = 0; j < 4; ++j) {
    const int p = physicalJointOfMotor(j, stance);
    motor(j) += s.encoder_offset[p];
    r.gamma(j) = s.torque_gain[p] * gamma_star(j) + s.torque_offset[p];
  }
  r.q = qFromMotorAngles(q(0) + s.alpha_offset, motor);
  return r;
}

}  // namespace gaitopt
