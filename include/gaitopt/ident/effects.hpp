#pragma once
// The candidate effects of `gaitopt diagnose` (what the thesis model may get wrong on a real
// robot), their value conventions, and how each changes a robot description
// (model/robot_params.hpp, JointExtras, SensorModel, hip_payload, trunk_com_shift, ground_slope,
// foot_radius, foot_offset). The same description
// is the TRUE model of `gaitopt synth` and the extended model fitted by `gaitopt diagnose`.
//
// Motors follow the thesis convention (1 = knee of leg 1, 2 = hip of leg 1, 3 = hip of leg 2,
// 4 = knee of leg 2) with leg 1 the stance leg (front leg in DS); physical joints are
// knee_left, hip_left, hip_right, knee_right.
#include <array>
#include <string>
#include <vector>

#include "gaitopt/model/model.hpp"
#include "gaitopt/model/robot_params.hpp"
#include "gaitopt/model/stance.hpp"

namespace gaitopt {

// Physical joint (0..3, kPhysicalJointNames order) driven by motor j (0..3) for a stance.
inline int physicalJointOfMotor(int j, Stance stance) { return stance == Stance::Left ? j : 3 - j; }

enum class EffectKind {
  Coulomb, Viscous, RotorInertia, TorqueOffset, TorqueGain, EncoderOffset, Backlash, Payload,
  TrunkCom, Slope, RockerFoot, FootOffset,
  // The base inertial parameters (ident/inertial_fit.hpp): many parameters, fitted by
  // `diagnose` as a last resort, not a one-parameter candidate nor a `synth` effect (change
  // the robot file's masses and inertias instead). withEffect leaves the robot unchanged.
  Inertial
};
constexpr int kNumEffectKinds = 13;
constexpr int kAlphaJoint = 4;  // encoder_offset on α
constexpr int kNoJoint = -1;

struct EffectInfo {
  const char* name;
  const char* unit;
  bool per_joint;   // on a physical joint (encoder_offset also on alpha)
  bool factor;      // value is a factor, neutral 1 (else additive, neutral 0)
  bool needs_torque;  // only visible through measured torques
  double step;      // finite-difference step and typical scale of the value
  bool linear;      // the predicted measurements are affine in the value
};
const EffectInfo& effectInfo(EffectKind kind);

struct Effect {
  EffectKind kind;
  int joint = kNoJoint;  // physical joint 0..3, kAlphaJoint, or kNoJoint
  double value = 0.0;    // in the convention of docs/commands/diagnose.md's effect table
};

std::string jointName(int joint);  // "knee_left".."knee_right", "alpha", or "" for none
std::string effectLabel(const Effect& e);  // "coulomb@knee_right"

// The VALUE of a spec: a finite number, all of `text` (std::invalid_argument otherwise).
double parseEffectValue(const std::string& text);

// Parses "NAME[@JOINT]=VALUE" (std::invalid_argument with the reason on a bad spec).
Effect parseEffectSpec(const std::string& spec);

// `robot` with the effect added (on top of what it already has).
RobotParams withEffect(RobotParams robot, const Effect& e);
RobotParams withEffects(RobotParams robot, const std::vector<Effect>& effects);

// The robot as the thesis model sees it for one stance: physical-joint friction and rotor
// factors folded into the motor-order arrays (the joint extras are then neutral).
RobotParams stanceRobot(const RobotParams& robot, Stance stance);

// The joint-side motor angles (δ1, −δ2, −(δ2+δ3), δ4) of q (1.19), and back.
Vec4 motorAngles(const Vec5& q);
Vec5 qFromMotorAngles(double alpha, const Vec4& motor);

// What the sensors read, for one stance, given the true state and true torques Γ*.
struct SensorReading {
  Vec5 q;      // measured α and δ
  Vec4 gamma;  // measured Γ*
};
SensorReading sensorReading(const SensorModel& s, Stance stance, const Vec5& q,
                            const Vec4& gamma_star);

// Backlash part of the encoder reading: backlash/2 × tanh(Γ*/1 N·m), per motor (1 N·m: the
// smoothing width of the dead band's sign).
Vec4 backlashShift(const SensorModel& s, Stance stance, const Vec4& gamma_star);

}  // namespace gaitopt
