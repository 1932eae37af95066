#include "gaitopt/ident/residual_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gaitopt/model/forward_dynamics.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"
#include "gaitopt/model/rocker_foot.hpp"

namespace gaitopt {

const std::array<const char*, kNumChannels> kChannelNames = {
    "alpha_row",        "gamma_knee_left", "gamma_hip_left", "gamma_hip_right",
    "gamma_knee_right", "R1x",             "R1z",            "R2x",
    "R2z",              "ds_foot2_z",      "cop1x"};
const std::array<const char*, kNumChannels> kChannelUnits = {
    "N·m", "N·m", "N·m", "N·m", "N·m", "N", "N", "N", "N", "m", "m"};

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct StanceModels {
  Model model[2];
  Vec4 gain[2], offset[2];
  double foot_radius, foot_offset, slope;
  StanceModels(const RobotParams& robot, const ModelOptions& options)
      : foot_radius(robot.foot_radius), foot_offset(robot.foot_offset), slope(robot.ground_slope) {
    for (int s = 0; s < 2; ++s) {
      const Stance stance = static_cast<Stance>(s);
      model[s] = buildModel(stanceRobot(robot, stance), options);
      for (int j = 0; j < 4; ++j) {
        const int p = physicalJointOfMotor(j, stance);
        gain[s](j) = robot.sensors.torque_gain[p];
        offset[s](j) = robot.sensors.torque_offset[p];
      }
    }
  }
};

bool hasBacklash(const SensorModel& s) {
  for (double b : s.backlash)
    if (b != 0.0) return true;
  return false;
}

// Link kinematics from the measured ones: minus the constant encoder offsets, and minus the
// backlash shift (a signal of the measured torques, differentiated by the same filter).
Kinematics linkKinematics(const PreparedData& p, const RobotParams& robot, const StanceModels& sm,
                          const Kinematics& measured, const SmoothingDifferentiator& differentiator) {
  Kinematics k = measured;
  const MeasuredData& d = p.data;
  const SensorModel& s = robot.sensors;
  std::vector<Vec5> shift(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    const int st = static_cast<int>(d.stance[i]);
    Vec4 motor;
    for (int j = 0; j < 4; ++j) motor(j) = s.encoder_offset[physicalJointOfMotor(j, d.stance[i])];
    k.q[i] -= qFromMotorAngles(s.alpha_offset, motor);
    if (d.has_torque && hasBacklash(s)) {
      const Vec4 gamma = (d.gamma[i] - sm.offset[st]).cwiseQuotient(sm.gain[st]);
      shift[i] = qFromMotorAngles(0.0, backlashShift(s, d.stance[i], gamma));
    }
  }
  if (d.has_torque && hasBacklash(s)) {
    const Kinematics b = differentiate(differentiator, shift);
    for (std::size_t i = 0; i < d.size(); ++i) {
      k.q[i] -= b.q[i];
      k.qd[i] -= b.qd[i];
      k.qdd[i] -= b.qdd[i];
    }
  }
  return k;
}

// Near a joint's velocity reversal the predicted Coulomb torque swings by 2 Γs within a few
// hundredths of rad/s, so a small velocity error there gives a large spurious residual: those
// samples say nothing reliable and are left out.
constexpr double kReversalSpeed = 0.2;  // [rad/s], 4 × the default friction smoothing width

void putGamma(const MeasuredData& d, std::size_t i, const Vec4& predicted, const Vec5& qd,
              double* row) {
  if (!d.has_torque) return;
  const Vec4 omega = jointSpeeds(qd);
  for (int j = 0; j < 4; ++j)
    if (std::abs(omega(j)) >= kReversalSpeed)
      row[kGammaKneeLeft + physicalJointOfMotor(j, d.stance[i])] = d.gamma[i](j) - predicted(j);
}

// The single-support equations at sample i: point foot, the pinned model; rocker foot, its
// equations in the ankle frame.
struct StanceForces {
  ChainState<double> state;
  RockerContact<double> contact;
  RockerForces<double> forces;
};

StanceForces stanceForces(const StanceModels& sm, const Model& m, const Kinematics& k, std::size_t i) {
  StanceForces f{chainState(m, k.q[i], k.qd[i]),
                 rockerContact(sm.foot_radius, sm.foot_offset, sm.slope, k.q[i](0), k.qd[i](0),
                               k.qdd[i](0)),
                 {}};
  f.forces = rockerForces(m, f.state, pinnedMotionForces(m, f.state, k.qdd[i]), f.contact);
  return f;
}

// With centres of pressure, the world x of the stance ankle over a single-support segment: the
// unloaded swing foot's (cop2x: an unloaded leg's point foot) minus the chain's swing foot
// relative to the stance ankle, averaged over the segment — the model's ankle stands still (a
// rolling foot's moves at second order in the tibia angle), a person's rises and rolls forward
// with the heel, which is the foot's own motion, part of the CoP's travel about it.
double stanceAnkleX(const MeasuredData& d, const Model& m, const Kinematics& k, const Segment& s) {
  double sum = 0.0;
  for (std::size_t i = s.begin; i < s.end; ++i)
    sum += d.cop[i][1] - chainPoint(m.pinned.foot2, chainState(m, k.q[i], k.qd[i]))(0);
  return sum / static_cast<double>(s.end - s.begin);
}

// With centres of pressure the foot moment about the point foot is measured, and the α row
// compares the dynamics with it: the model's ground moment about the stance ankle is replaced
// by the measured one (the foot is then checked by the cop1x channel, not inferred from the
// dynamics). The measured moment is the measured reaction at the measured CoP; its arm along x
// is the CoP's from the stance ankle (`ankle`, stanceAnkleX), its height the model's (the data
// do not say how far the contact lies below the ankle). Returns the model's moment minus the
// measured one.
double footMomentError(const MeasuredData& d, const StanceForces& f, double ankle, std::size_t i) {
  const Vec2& arm = f.contact.contact_arm;
  const Vec2 measured_arm(d.cop[i][0] - ankle, arm(1));
  const auto moment = [](const Vec2& r, const Vec2& force) { return r(0) * force(1) - r(1) * force(0); };
  return moment(arm, f.forces.reaction) - moment(measured_arm, d.reactions[i].head<2>());
}

// `ankle`: the stance ankle's world x (stanceAnkleX) when the data have centres of pressure.
void singleSupportRow(const PreparedData& p, const StanceModels& sm, const Kinematics& k,
                      const Kinematics& ka, double ankle, std::size_t i, double* row) {
  const MeasuredData& d = p.data;
  const int st = static_cast<int>(d.stance[i]);
  const Model& m = sm.model[st];
  const RockerForces<double> rf = stanceForces(sm, m, k, i).forces;
  const StanceForces fa = stanceForces(sm, m, ka, i);  // the α row's own, smoother, kinematics
  row[kAlphaRow] = fa.forces.tau(0);
  if (d.has_cop) row[kAlphaRow] += m.theta_map(0, 0) * footMomentError(d, fa, ankle, i);
  const Vec4 gamma = solveDGamma25(Vec4(rf.tau.tail<4>())) +
                     frictionTorque(m, jointSpeeds(k.qd[i]), SignMode::Smooth);  // (3.57)
  putGamma(d, i, sm.gain[st].cwiseProduct(gamma) + sm.offset[st], k.qd[i], row);
  if (d.has_reactions) {
    const Vec4 predicted(rf.reaction(0), rf.reaction(1), 0, 0);  // (1.36)
    for (int c = 0; c < 4; ++c) row[kR1x + c] = d.reactions[i](c) - predicted(c);
  }
}

void doubleSupportRow(const PreparedData& p, const StanceModels& sm, const Kinematics& k,
                      double slope, std::size_t i, double* row) {
  const MeasuredData& d = p.data;
  const int st = static_cast<int>(d.stance[i]);
  const Model& m = sm.model[st];
  const PinnedMotionForces<double> f = pinnedMotionForces(m, chainState(m, k.q[i], k.qd[i]), k.qdd[i]);
  const DoubleSupportAffine<double> a = doubleSupportAffine(m, f, k.qd[i], SignMode::Smooth);
  double r2x;
  if (d.has_reactions) {
    r2x = d.reactions[i](2);
  } else {  // the R2x that best explains the measured torques
    const Vec4 gamma = (d.gamma[i] - sm.offset[st]).cwiseQuotient(sm.gain[st]);
    r2x = a.K.dot(a.J - gamma) / a.K.squaredNorm();
  }
  putGamma(d, i, sm.gain[st].cwiseProduct(a.J - a.K * r2x) + sm.offset[st], k.qd[i], row);  // (3.62)
  if (d.has_reactions) {
    const double M = m.total_mass;
    const double r2z = a.R2z0 + a.R2z_slope * r2x;  // (3.58)
    row[kR1x] = d.reactions[i](0) - M * a.com_acceleration(0) + r2x;  // (3.59)
    row[kR1z] = d.reactions[i](1) - (M * (a.com_acceleration(1) + m.gravity) - r2z);
    row[kR2z] = d.reactions[i](3) - r2z;
  }
  row[kFoot2z] = f.foot2(1) - f.foot2(0) * std::tan(slope);
}

// The cop1x channel of a single-support segment (residual_model.hpp): measured minus predicted
// contact-point travel, each about its mean over the segment, at the segment's samples of `rows`.
void copTravelRows(const PreparedData& p, const RobotParams& robot, const Kinematics& k,
                   const Segment& s, const std::vector<char>& rows, ResidualMatrix& r) {
  const MeasuredData& d = p.data;
  const auto predicted = [&](std::size_t i) {  // rolling without slipping, along the ground
    return -robot.foot_radius * (k.q[i](0) - robot.ground_slope) * std::cos(robot.ground_slope);
  };
  double mean = 0.0;
  for (std::size_t i = s.begin; i < s.end; ++i) mean += d.cop[i][0] - predicted(i);
  mean /= static_cast<double>(s.end - s.begin);
  for (std::size_t i = s.begin; i < s.end; ++i)
    if (rows[i]) r(i, kCopX) = d.cop[i][0] - predicted(i) - mean;
}

}  // namespace

PreparedData::PreparedData(const MeasuredData& d, const PreprocessOptions& o)
    : data(d),
      segments(dataSegments(d)),
      differentiator(d.t, segments, o.half_window, o.order),
      alpha_row_differentiator(d.t, segments, o.alpha_row_half_window, o.alpha_row_order),
      measured(differentiate(differentiator, d.q)),
      measured_alpha_row(differentiate(alpha_row_differentiator, d.q)) {}

ResidualMatrix residuals(const PreparedData& p, const RobotParams& robot,
                         const ModelOptions& model_options, const std::vector<char>& rows) {
  const StanceModels sm(robot, model_options);
  const Kinematics k = linkKinematics(p, robot, sm, p.measured, p.differentiator);
  const Kinematics ka = linkKinematics(p, robot, sm, p.measured_alpha_row, p.alpha_row_differentiator);
  ResidualMatrix r = ResidualMatrix::Constant(p.data.size(), kNumChannels, kNaN);
  for (const Segment& s : p.segments) {
    const bool ss = s.phase == Phase::SingleSupport, cop = ss && p.data.has_cop;
    const double ankle = cop ? stanceAnkleX(p.data, sm.model[static_cast<int>(s.stance)], k, s) : kNaN;
    for (std::size_t i = s.begin; i < s.end; ++i) {
      if (!rows[i]) continue;
      if (ss)
        singleSupportRow(p, sm, k, ka, ankle, i, r.row(i).data());
      else
        doubleSupportRow(p, sm, k, robot.ground_slope, i, r.row(i).data());
    }
    if (cop) copTravelRows(p, robot, k, s, rows, r);
  }
  return r;
}

Eigen::VectorXd simulationError(const PreparedData& p, const RobotParams& robot,
                                const ModelOptions& model_options, const std::vector<char>& rows) {
  const MeasuredData& d = p.data;
  if (!d.has_torque) return Eigen::VectorXd();
  const StanceModels sm(robot, model_options);
  const Kinematics k = linkKinematics(p, robot, sm, p.measured, p.differentiator);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(6);
  double count = 0.0;
  for (const Segment& s : p.segments) {
    if (s.phase != Phase::SingleSupport || !rows[s.begin]) continue;
    const int st = static_cast<int>(s.stance);
    const auto torque = [&](double t, const PinnedState&) {  // measured, linearly interpolated
      std::size_t i = s.begin;
      while (i + 2 < s.end && d.t[i + 1] <= t) ++i;
      const double w = std::clamp((t - d.t[i]) / (d.t[i + 1] - d.t[i]), 0.0, 1.0);
      const Vec4 g = (1.0 - w) * d.gamma[i] + w * d.gamma[i + 1];
      return Vec4((g - sm.offset[st]).cwiseQuotient(sm.gain[st]));
    };
    PinnedState x{k.q[s.begin], k.qd[s.begin]};
    for (std::size_t i = s.begin + 1; i < s.end; ++i) {
      const double t0 = d.t[i - 1];
      const TorqueLaw law = [&](double t, const PinnedState& y) { return torque(t0 + t, y); };
      x = simulateSS(sm.model[st], x, law, d.t[i] - t0, d.t[i] - t0, SignMode::Smooth);
      const Vec5 e = x.q - k.q[i];
      Vec4 joint;
      for (int j = 0; j < 4; ++j)
        joint(physicalJointOfMotor(j, s.stance)) = motorAngles(e)(j);
      sum(0) += e(0) * e(0);
      for (int j = 0; j < 4; ++j) sum(1 + j) += joint(j) * joint(j);
      count += 1.0;
    }
  }
  if (count == 0.0) return Eigen::VectorXd();
  sum(5) = sum.head<5>().sum() / 5.0;
  return (sum / count).cwiseSqrt();
}

}  // namespace gaitopt
