// Physical ranges of the library's effects, from the robot file where they depend on it.
#include "gaitopt/ident/admissible_range.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

namespace gaitopt {

namespace {

// Fractions of the robot's scales that bound an effect (docs/commands/diagnose.md, the effect table).
constexpr double kSensorOffsetShare = 0.04;   // |torque_offset| < 4 % of the peak torque
constexpr double kCoulombShare = 0.1;         // extra Coulomb < 10 % of the peak torque
constexpr double kViscousShare = 0.5;         // extra viscous torque at the corner speed < 50 %
constexpr double kMaxRotorFactor = 4.0;
constexpr double kGainSpan = 0.3;             // torque_gain in (0.7, 1.3)
constexpr double kMaxEncoderOffset = 0.1;     // rad: a mounting error, not a wrong zero by turns
constexpr double kMaxBacklash = 0.1;          // rad
constexpr double kPayloadLow = 0.25, kPayloadHigh = 0.5;  // of the total mass
constexpr double kTrunkComShare = 0.25;       // of the trunk length
constexpr double kMaxSlope = 0.15;            // rad (8.6°)
constexpr double kRockerShare = 1.0;          // of the leg length: the arc's centre below the hip
constexpr double kFootOffsetShare = 0.25;     // of the leg length

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

double totalMass(const RobotParams& r) {
  double m = r.hip_payload + (r.bar.present ? r.bar.equivalent_mass : 0.0);
  for (double mi : r.mass) m += mi;
  return m;
}

double legLength(const RobotParams& r) { return std::min(r.l1 + r.l2, r.l4 + r.l5); }

// The smaller of the two motors' values a physical joint gets (it is motor p in left stance and
// motor 3 − p in right stance), plus its joint extra.
double jointValue(const std::array<double, 4>& motor, const std::array<double, 4>& extra, int p) {
  return std::min(motor[p], motor[3 - p]) + extra[p];
}

}  // namespace

AdmissibleRange admissibleRange(const Effect& e, const RobotParams& r) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double peak = *std::max_element(r.envelope.torque.begin(), r.envelope.torque.end());
  const double corner = r.envelope.speed[1] > 0.0 ? r.envelope.speed[1] : 1.0;
  const int p = e.joint;
  switch (e.kind) {
    case EffectKind::Coulomb:
      return {-jointValue(r.coulomb, r.joint_extras.coulomb, p), kCoulombShare * peak,
              "total friction >= 0, extra < 10 % of the peak torque " + fmt("%g", peak) + " N·m"};
    case EffectKind::Viscous:
      return {-jointValue(r.viscous, r.joint_extras.viscous, p), kViscousShare * peak / corner,
              "total friction >= 0, extra torque at the corner speed " + fmt("%g", corner) +
                  " rad/s < 50 % of the peak torque"};
    case EffectKind::RotorInertia: return {0.0, kMaxRotorFactor, "factor > 0, at most 4"};
    case EffectKind::TorqueOffset:
      return {-kSensorOffsetShare * peak, kSensorOffsetShare * peak,
              "±4 % of the peak torque " + fmt("%g", peak) + " N·m"};
    case EffectKind::TorqueGain: return {1.0 - kGainSpan, 1.0 + kGainSpan, "±30 % calibration error"};
    case EffectKind::EncoderOffset:
      return {-kMaxEncoderOffset, kMaxEncoderOffset, "±0.1 rad mounting error"};
    case EffectKind::Backlash: return {0.0, kMaxBacklash, "dead band >= 0, below 0.1 rad"};
    case EffectKind::Payload: {
      const double m = totalMass(r);
      return {-kPayloadLow * m, kPayloadHigh * m,
              "-25 % to +50 % of the total mass " + fmt("%.3g", m) + " kg"};
    }
    case EffectKind::TrunkCom: {
      const double s3 = r.s[2] + r.trunk_com_shift;
      const double span = kTrunkComShare * r.trunk_length;
      return {std::max(-span, -s3), std::min(span, r.trunk_length - s3),
              "±0.25 × trunk length " + fmt("%g", r.trunk_length) + " m, CoM on the trunk"};
    }
    case EffectKind::Slope: return {-kMaxSlope, kMaxSlope, "±0.15 rad walking ground"};
    case EffectKind::RockerFoot:
      return {-r.foot_radius, kRockerShare * legLength(r) - r.foot_radius,
              "radius >= 0, below the leg length " + fmt("%g", legLength(r)) + " m"};
    case EffectKind::FootOffset: {
      const double span = kFootOffsetShare * legLength(r);
      return {-span - r.foot_offset, span - r.foot_offset,
              "±0.25 × leg length " + fmt("%g", legLength(r)) + " m"};
    }
    case EffectKind::Inertial: break;
  }
  return {-inf, inf, "physically consistent by construction"};
}

AdmissibleRange synthesisRange(const Effect& e, const RobotParams& r) {
  const AdmissibleRange a = admissibleRange(e, r);
  if (e.kind == EffectKind::Inertial) return a;
  const double neutral = effectInfo(e.kind).factor ? 1.0 : 0.0;
  AdmissibleRange g{neutral + kSynthesisRangeMultiple * (a.lo - neutral),
                    neutral + kSynthesisRangeMultiple * (a.hi - neutral),
                    "the admissible range (" + fmt("%.3g", a.lo) + ", " + fmt("%.3g", a.hi) +
                        ") stretched " + fmt("%g", kSynthesisRangeMultiple) +
                        " times about the neutral value, its physical laws kept: " + a.basis};
  switch (e.kind) {
    case EffectKind::Coulomb:
    case EffectKind::Viscous:
    case EffectKind::Backlash:
    case EffectKind::RockerFoot: g.lo = a.lo + 0.0; break;  // a law: the total stays >= 0
    case EffectKind::RotorInertia:
    case EffectKind::TorqueGain: g.lo = std::max(g.lo, 0.0); break;
    case EffectKind::Payload: g.lo = std::max(g.lo, -totalMass(r)); break;
    default: break;
  }
  return g;
}

std::string inadmissibleReason(const Effect& e, const AdmissibleRange& range) {
  const std::string unit = effectInfo(e.kind).unit;
  return effectLabel(e) + " " + fmt("%.3g", e.value) + " " + unit +
         " is outside its physical range (" + fmt("%.3g", range.lo) + ", " +
         fmt("%.3g", range.hi) + ") " + unit + ": " + range.basis;
}

std::string firstInadmissible(const std::vector<Effect>& effects, const RobotParams& robot) {
  for (const Effect& e : effects) {
    const AdmissibleRange range = admissibleRange(e, robot);
    if (!range.contains(e.value)) return inadmissibleReason(e, range);
  }
  return "";
}

}  // namespace gaitopt
