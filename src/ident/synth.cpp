#include "gaitopt/ident/synth.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>

#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/math/decimal.hpp"
#include "gaitopt/gait/phase_sample.hpp"
#include "gaitopt/model/dynamics_floating.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"
#include "gaitopt/model/rocker_foot.hpp"

namespace gaitopt {

namespace {

struct TrueSample {
  Phase phase;
  Vec5 q;  // gravity frame
  Vec4 gamma_star;
  Vec4 reactions;
  std::array<double, 2> cop{};  // world x of the centres of pressure under leg 1, leg 2
};

// One step's gait variation: velocities, the interior SS point and T_DS move a little, the
// DS/SS boundary configurations and the step length stay (the feet stay on the ground).
GaitParameters varied(const GaitParameters& p, std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  GaitParameters v = p;
  v(kAlphadotISS) *= 1.0 + 0.04 * scale * u(rng);
  for (int k : {kDelta1sISS, kDelta2sISS, kDelta1sFSS, kDelta2sFSS}) v(k) += 0.05 * scale * u(rng);
  v(kDelta1Int) += 0.01 * scale * u(rng);
  v(kTheta3Int) += 0.01 * scale * u(rng);
  v(kZ2Int) += 0.003 * scale * u(rng);
  v(kTDS) *= 1.0 + 0.05 * scale * u(rng);
  return v;
}

Vec5 toGravityFrame(Vec5 q, double slope) {
  q(0) += slope;  // the gait's frame is the ground's; α is measured from the vertical
  return q;
}

TrueSample dsTrueSample(const Model& m, const GaitOptions& o, const GaitMotion<double>& mo,
                        double t, double slope) {
  const PhaseSample<double> k = dsSample(m, o, mo, t);
  const Vec5 q = toGravityFrame(k.q, slope);
  const DoubleSupportAffine<double> a = doubleSupportAffine(m, q, k.qd, k.qdd, SignMode::Smooth);
  const double r2x = a.K.dot(a.J) / a.K.squaredNorm();  // min ‖J − K R2x‖² (3.60), unbounded
  const DoubleSupportInverseDynamics<double> id =
      inverseDynamicsDS(m, q, k.qd, k.qdd, r2x, SignMode::Smooth);
  return {Phase::DoubleSupport, q, id.gamma_star, Vec4(id.R1(0), id.R1(1), id.R2(0), id.R2(1))};
}

// Single support of a rocker foot (model/rocker_foot.hpp) on the SS path at (α, α̇), from the
// floating model (1.1) with the rolling constraint — a formulation independent of the
// ankle-frame equations diagnose fits. X = (q, trunk CoM), the trunk CoM following the ankle
// A(α); in A Ẍ + C + G = D_Γ Γ + D1ᵀ R + T₁ᵀ ((P − A) × R) the α, x and z rows have no Γ and
// are affine in (α̈, R): they give α̈ and the reaction; the joint rows then give Γ.
struct RollingSolution {
  double alphadd;
  Vec5 q, qd, qdd;
  Vec2 reaction;
  Vec4 gamma;  // after friction
};

RollingSolution rollingFootSS(const Model& m, double radius, double offset, double slope, const Vec5& q,
                              const Vec5& qs, const Vec5& qss, double alphad) {
  const Vec5 trunk = m.pinned.body.row(2).transpose();
  const Vec5 qd = qs * alphad;
  const ChainState<double> st = chainState(m, q, qd);
  const auto residual = [&](double alphadd, const Vec2& R, Vec5* qdd_out) {
    const Vec5 qdd = qs * alphadd + qss * alphad * alphad;
    const RockerContact<double> c = rockerContact(radius, offset, slope, q(0), alphad, alphadd);
    Vector7<double> X, Xd, Xdd;
    X << q, chainPoint(trunk, st);  // ankle position: the terms do not depend on it
    Xd << qd, c.ankle_jacobian * alphad + chainPointVelocity(trunk, st);
    Xdd << qdd, c.ankle_acceleration + chainPointAcceleration(trunk, st, Vec5(m.theta_map * qdd));
    const FloatingTerms<double> t = floatingTerms(m, X, Xd);
    Vector7<double> h = t.A * Xdd + t.C + t.G - t.D1.transpose() * R;
    h.head<5>() -= (c.contact_arm(0) * R(1) - c.contact_arm(1) * R(0)) * m.theta_map.row(0).transpose();
    if (qdd_out) *qdd_out = qdd;
    return h;
  };
  const Vector7<double> h0 = residual(0.0, Vec2::Zero(), nullptr);
  const Vector7<double> columns[3] = {residual(1.0, Vec2::Zero(), nullptr) - h0,
                                      residual(0.0, Vec2(1, 0), nullptr) - h0,
                                      residual(0.0, Vec2(0, 1), nullptr) - h0};
  Eigen::Matrix3d K;
  Eigen::Vector3d rhs;
  const int rows[3] = {0, 5, 6};  // α, x, z
  for (int i = 0; i < 3; ++i) {
    rhs(i) = -h0(rows[i]);
    for (int j = 0; j < 3; ++j) K(i, j) = columns[j](rows[i]);
  }
  const Eigen::Vector3d x = K.partialPivLu().solve(rhs);
  RollingSolution s;
  s.alphadd = x(0);
  s.reaction = x.tail<2>();
  s.q = q;
  s.qd = qd;
  const Vector7<double> h = residual(s.alphadd, s.reaction, &s.qdd);
  s.gamma = solveDGamma25(Vec4(h.segment<4>(1)));
  return s;
}

// Zero dynamics of the SS path δ = h(α) (α-row of (1.32), no foot torque) in the gravity
// frame: α̈ = −(τ_c α̇² + G)/τ_a with τ_a, τ_c slope-independent (relative angles only); with
// a rocker foot, α̈ of the rolling model.
struct ZeroDynamics {
  const Model& m;
  const GaitMotion<double>& mo;
  double slope;
  double foot_radius, foot_offset;
  SsPathPoint<double> point(double alpha) const {
    return ssPathPoint(m, mo, alpha);
  }
  RollingSolution rolling(const SsPathPoint<double>& pt, double alphadot) const {
    return rollingFootSS(m, foot_radius, foot_offset, slope, toGravityFrame(pt.q, slope), pt.qs, pt.qss, alphadot);
  }
  double acceleration(const SsPathPoint<double>& pt, double alphadot) const {
    if (foot_radius != 0.0 || foot_offset != 0.0) return rolling(pt, alphadot).alphadd;
    const ChainState<double> st =
        chainState(m, toGravityFrame(pt.q, slope), Vec5(Vec5::Zero()));
    const double g0 =
        constantTimes(m.theta_map_transpose, chainGravityTheta(m.pinned, m.gravity, st))(0);
    return -(pt.tau_c(0) * alphadot * alphadot + g0) / pt.tau_a(0);
  }
  Vec2 rate(const Vec2& x) const { return Vec2(x(1), acceleration(point(x(0)), x(1))); }
  Vec2 advance(Vec2 x, double h) const {  // classical RK4
    const Vec2 k1 = rate(x), k2 = rate(x + 0.5 * h * k1), k3 = rate(x + 0.5 * h * k2),
               k4 = rate(x + h * k3);
    return x + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
};

TrueSample ssTrueSample(const Model& m, const ZeroDynamics& zd, const Vec2& x) {
  const SsPathPoint<double> pt = zd.point(x(0));
  if (zd.foot_radius != 0.0 || zd.foot_offset != 0.0) {
    const RollingSolution r = zd.rolling(pt, x(1));
    const Vec4 gamma_star = r.gamma + frictionTorque(m, jointSpeeds(r.qd), SignMode::Smooth);
    return {Phase::SingleSupport, r.q, gamma_star, Vec4(r.reaction(0), r.reaction(1), 0.0, 0.0)};
  }
  const double add = zd.acceleration(pt, x(1));
  const Vec5 q = toGravityFrame(pt.q, zd.slope);
  const Vec5 qd = pt.qs * x(1), qdd = pt.qs * add + pt.qss * x(1) * x(1);
  const SingleSupportInverseDynamics<double> id =
      inverseDynamicsSS(m, q, qd, qdd, SignMode::Smooth);
  return {Phase::SingleSupport, q, id.gamma_star, Vec4(id.R1(0), id.R1(1), 0.0, 0.0)};
}

// Samples of one step at times k/rate from its start; empty if the TRUE zero dynamics stall.
std::vector<TrueSample> stepSamples(const Model& m, const GaitOptions& o,
                                    const GaitMotion<double>& mo, const RobotParams& truth,
                                    double rate) {
  const double slope = truth.ground_slope;
  std::vector<TrueSample> out;
  const double dt = 1.0 / rate;
  int k = 0;
  for (; k * dt < mo.T_DS; ++k) out.push_back(dsTrueSample(m, o, mo, k * dt, slope));
  const ZeroDynamics zd{m, mo, slope, truth.foot_radius, truth.foot_offset};
  const double direction = mo.alpha_fSS < mo.alpha_iSS ? -1.0 : 1.0;
  Vec2 x(mo.alpha_iSS, mo.alphadot_iSS);
  double t = mo.T_DS;
  const double h_max = dt / 4.0;
  for (;; ++k) {
    const double target = k * dt;
    const int n = std::max(1, static_cast<int>(std::ceil((target - t) / h_max - 1e-9)));
    for (int i = 0; i < n; ++i) x = zd.advance(x, (target - t) / n);
    t = target;
    if (!(x(1) * direction > 0.0)) return {};  // the TRUE robot falls back
    if ((x(0) - mo.alpha_fSS) * direction >= 0.0) break;
    out.push_back(ssTrueSample(m, zd, x));
  }
  return out;
}

struct Noise {
  std::mt19937_64 rng;
  const SynthOptions& o;
  std::mt19937_64 cop_rng;  // a stream of its own: the other noise does not depend on it
  double quantised(double angle) const {
    if (!o.noise) return angle;
    const double count = 2.0 * M_PI / o.encoder_counts;
    return std::round(angle / count) * count;
  }
  Vec4 gaussian(double sigma) {
    std::normal_distribution<double> n(0.0, sigma);
    Vec4 v;
    for (int j = 0; j < 4; ++j) v(j) = o.noise ? n(rng) : 0.0;
    return v;
  }
  std::array<double, 2> cop(const std::array<double, 2>& x) {
    std::normal_distribution<double> n(0.0, o.cop_noise);
    return o.noise ? std::array<double, 2>{x[0] + n(cop_rng), x[1] + n(cop_rng)} : x;
  }
};

// The knee_centre torques (synth.hpp) of sample s, per motor.
Vec4 kneeCentreTorque(const Model& m, Stance stance, const TrueSample& s,
                      const std::vector<UnmodelledEffect>& effects) {
  Vec4 torque = Vec4::Zero();
  const Vec5 theta = m.theta_map * s.q + m.theta_offset;
  for (const UnmodelledEffect& e : effects) {
    if (e.kind != UnmodelledKind::KneeCentre) continue;
    const int motor = physicalJointOfMotor(e.joint, stance);  // the map is its own inverse
    const bool leg1 = motor == 0;
    const int femur = leg1 ? 1 : 3, tibia = leg1 ? 0 : 4;
    const Vec2 reaction = s.reactions.segment<2>(leg1 ? 0 : 2);
    const Vec2 force(-reaction(0), m.mass(tibia) * m.gravity - reaction(1));
    const double flexion = std::abs(motorAngles(s.q)(motor) + M_PI);
    const Vec2 along(std::cos(theta(femur)), std::sin(theta(femur)));
    torque(motor) += e.value * (1.0 + flexion) * force.dot(along);
  }
  return torque;
}

// The ground_compliance forces (synth.hpp) of one step's single support: the stance foot sinks
// by s = R1z/K, s̈ by second differences of the samples (one-sided at the phase ends).
void addGroundCompliance(const Model& m, double stiffness, double rate, std::vector<TrueSample>& samples) {
  std::size_t a = 0;
  while (a < samples.size() && samples[a].phase != Phase::SingleSupport) ++a;
  const std::size_t n = samples.size() - a;
  if (n < 3) return;
  std::vector<double> sdd(n);
  const auto sink = [&](std::size_t i) { return samples[a + i].reactions(1) / stiffness; };
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t c = std::clamp<std::size_t>(i, 1, n - 2);
    sdd[i] = (sink(c + 1) - 2.0 * sink(c) + sink(c - 1)) * rate * rate;
  }
  for (std::size_t i = 0; i < n; ++i) {
    TrueSample& s = samples[a + i];
    const Vec2 ankle_acceleration(0.0, -sdd[i]);
    const ChainState<double> st = chainState(m, s.q, Vec5(Vec5::Zero()));
    const Vec5 tau = chainPointJacobian(m, m.pinned.b, st).transpose() * ankle_acceleration;
    s.gamma_star += solveDGamma25(Vec4(tau.tail<4>()));
    s.reactions.head<2>() += m.total_mass * ankle_acceleration;
  }
}

// The centres of pressure of one step (synth.hpp): leg 1's ankle stands at `foot` (world x) in
// double support, where both feet are points; in single support leg 1's contact rolls with the
// rocker foot, offset − r (α − slope) along the ground from that ankle. Leg 2 is its point foot
// (unloaded in single support). `foot` is the previous step's leg 1, this step's rear foot, on
// entry.
void setCentresOfPressure(const Model& m, const RobotParams& truth, std::vector<TrueSample>& samples,
                          double& foot) {
  const auto rear = [&](const TrueSample& s) {  // leg 2's foot relative to leg 1's ankle
    return chainPoint(m.pinned.foot2, chainState(m, s.q, Vec5(Vec5::Zero())))(0);
  };
  foot -= rear(samples.front());
  for (TrueSample& s : samples) {
    const double slope = truth.ground_slope;
    const double roll = truth.foot_offset - truth.foot_radius * (s.q(0) - slope);
    s.cop = {s.phase == Phase::DoubleSupport ? foot : foot + roll * std::cos(slope), foot + rear(s)};
  }
}

void appendMeasured(const SensorModel& sensors, Stance stance, long step, double t,
                    const TrueSample& s, Noise& noise, MeasuredData& d) {
  const SensorReading r = sensorReading(sensors, stance, s.q, s.gamma_star);
  Vec4 motor = motorAngles(r.q);
  for (const UnmodelledEffect& e : noise.o.unmodelled)
    if (e.kind == UnmodelledKind::JointCompliance) {
      const int j = physicalJointOfMotor(e.joint, stance);
      motor(j) += s.gamma_star(j) / e.value;
    }
  for (int j = 0; j < 4; ++j) motor(j) = noise.quantised(motor(j));
  d.t.push_back(t);
  d.q.push_back(qFromMotorAngles(noise.quantised(r.q(0)), motor));
  d.phase.push_back(s.phase);
  d.stance.push_back(stance);
  d.step.push_back(step);
  d.gamma.push_back(r.gamma + noise.gaussian(noise.o.torque_noise));
  d.reactions.push_back(s.reactions + noise.gaussian(noise.o.force_noise));
  d.cop.push_back(noise.cop(s.cop));
}

}  // namespace

MeasuredData synthesize(const RobotParams& robot, const GaitParameters& gait,
                        const GaitOptions& gait_options, const ModelOptions& model_options,
                        const std::vector<Effect>& effects, const SynthOptions& options) {
  const RobotParams truth = withEffects(robot, effects);
  // The evaluators give each step's motion; the dynamics use the full TRUE models (an evaluator
  // leaves Coulomb friction out of its model unless the gait asks for dry friction).
  std::optional<GaitEvaluator> evaluators[2];
  Model models[2];
  for (Stance s : {Stance::Left, Stance::Right}) {
    evaluators[static_cast<int>(s)].emplace(stanceRobot(truth, s), gait_options, model_options);
    models[static_cast<int>(s)] = buildModel(stanceRobot(truth, s), model_options);
  }
  // Separate streams: the same seed gives the same motion with and without noise.
  std::mt19937_64 excitation(options.seed);
  Noise noise{std::mt19937_64(options.seed ^ 0x9E3779B97F4A7C15ULL), options,
              std::mt19937_64(options.seed ^ 0xC2B2AE3D27D4EB4FULL)};
  MeasuredData d;
  d.has_torque = d.has_reactions = d.has_cop = true;
  double t0 = 0.0, foot = 0.0;
  for (int step = 0; step < options.steps; ++step) {
    const Stance stance = step % 2 == 0 ? Stance::Left : Stance::Right;
    const GaitEvaluator& ev = *evaluators[static_cast<int>(stance)];
    std::vector<TrueSample> samples;
    for (int attempt = 0; attempt < 40 && samples.empty(); ++attempt) {
      const double scale = options.variation / (1.0 + attempt / 10);
      const GaitEvaluation<double> e = ev.evaluate(varied(gait, excitation, scale));
      if (e.motion_computed && !e.numerically_undefined)
        samples = stepSamples(models[static_cast<int>(stance)], gait_options, e.motion, truth,
                              options.rate);
    }
    if (samples.empty())
      throw std::runtime_error("synth: step " + std::to_string(step) +
                               ": no variation of the gait is walkable by the TRUE model");
    for (TrueSample& sample : samples)
      sample.gamma_star += kneeCentreTorque(models[static_cast<int>(stance)], stance, sample, options.unmodelled);
    for (const UnmodelledEffect& e : options.unmodelled)
      if (e.kind == UnmodelledKind::GroundCompliance)
        addGroundCompliance(models[static_cast<int>(stance)], e.value, options.rate, samples);
    setCentresOfPressure(models[static_cast<int>(stance)], truth, samples, foot);
    for (std::size_t k = 0; k < samples.size(); ++k)
      appendMeasured(truth.sensors, stance, step, t0 + k / options.rate, samples[k], noise, d);
    t0 += samples.size() / options.rate;
  }
  return d;
}

Effect randomEffect(EffectKind kind, std::mt19937_64& rng, bool low) {
  const auto u = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  // A magnitude from [small, large], or from its lowest quarter.
  const auto mag = [&](double small, double large) { return u(small, low ? small + 0.25 * (large - small) : large); };
  const auto sign = [&] { return u(0.0, 1.0) < 0.5 ? -1.0 : 1.0; };
  const auto joint = [&](int n) { return std::min(n - 1, static_cast<int>(u(0.0, n))); };
  switch (kind) {
    case EffectKind::Coulomb: return {kind, joint(4), mag(1.0, 6.0)};
    case EffectKind::Viscous: return {kind, joint(4), mag(1.0, 6.0)};
    case EffectKind::RotorInertia: return {kind, joint(4), mag(1.3, 2.0)};
    case EffectKind::TorqueOffset: return {kind, joint(4), sign() * mag(1.0, 5.0)};
    case EffectKind::TorqueGain:
      return {kind, joint(4), u(0.0, 1.0) < 0.5 ? u(low ? 0.925 : 0.85, 0.95) : mag(1.05, 1.2)};
    case EffectKind::EncoderOffset: return {kind, joint(5), sign() * mag(0.01, 0.05)};
    case EffectKind::Backlash: return {kind, joint(4), mag(0.01, 0.04)};
    case EffectKind::Payload: return {kind, kNoJoint, mag(2.0, 8.0)};
    case EffectKind::TrunkCom: return {kind, kNoJoint, sign() * mag(0.02, 0.05)};
    case EffectKind::Slope: return {kind, kNoJoint, mag(0.01, 0.04)};
    case EffectKind::RockerFoot: return {kind, kNoJoint, mag(0.02, 0.1)};
    case EffectKind::FootOffset: return {kind, kNoJoint, sign() * mag(0.01, 0.04)};
    case EffectKind::Inertial: throw std::invalid_argument("inertial is not a synth effect");
  }
  return {kind};
}

UnmodelledEffect randomUnmodelled(UnmodelledKind kind, std::mt19937_64& rng, bool low) {
  const auto u = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  const int joint = std::min(3, static_cast<int>(u(0.0, 4.0)));
  switch (kind) {
    case UnmodelledKind::KneeCentre: return {kind, joint < 2 ? 0 : 3, u(0.01, low ? 0.0125 : 0.02)};
    case UnmodelledKind::JointCompliance: return {kind, joint, u(low ? 3500.0 : 2000.0, 4000.0)};
    case UnmodelledKind::GroundCompliance: return {kind, kNoJoint, u(low ? 6250.0 : 4000.0, 7000.0)};
  }
  return {kind};
}

const char* unmodelledName(UnmodelledKind kind) {
  static const char* names[kNumUnmodelledKinds] = {"knee_centre", "joint_compliance", "ground_compliance"};
  return names[static_cast<int>(kind)];
}

const char* unmodelledUnit(UnmodelledKind kind) {
  static const char* units[kNumUnmodelledKinds] = {"m/rad", "N·m/rad", "N/m"};
  return units[static_cast<int>(kind)];
}

UnmodelledEffect parseUnmodelledSpec(const std::string& spec) {
  const std::size_t eq = spec.find('='), at = spec.find('@');
  if (eq == std::string::npos || (at != std::string::npos && at > eq))
    throw std::invalid_argument("expected NAME@JOINT=VALUE or ground_compliance=VALUE");
  const std::string name = spec.substr(0, std::min(at, eq));
  const std::string joint = at == std::string::npos ? "" : spec.substr(at + 1, eq - at - 1);
  UnmodelledEffect e;
  bool known = false;
  for (int k = 0; k < kNumUnmodelledKinds; ++k)
    if (name == unmodelledName(static_cast<UnmodelledKind>(k))) {
      e.kind = static_cast<UnmodelledKind>(k);
      known = true;
    }
  if (!known)
    throw std::invalid_argument("unknown unmodelled effect '" + name + "'");
  e.joint = -1;
  for (int j = 0; j < 4; ++j)
    if (joint == kPhysicalJointNames[j]) e.joint = j;
  if (e.kind == UnmodelledKind::GroundCompliance) {
    if (!joint.empty() || at != std::string::npos)
      throw std::invalid_argument("ground_compliance takes no joint: ground_compliance=VALUE");
    e.joint = kNoJoint;
  } else if (e.joint < 0 || (e.kind == UnmodelledKind::KneeCentre && e.joint != 0 && e.joint != 3)) {
    throw std::invalid_argument("unknown joint '" + joint + "' for " + name);
  }
  e.value = parseEffectValue(spec.substr(eq + 1));
  if (e.value <= 0.0) throw std::invalid_argument(name + " must be > 0");
  return e;
}

AdmissibleRange unmodelledRange(const UnmodelledEffect& e, const RobotParams& r) {
  if (e.kind == UnmodelledKind::KneeCentre) {
    const double femur = std::min(r.l2, r.l4);
    return {0.0, femur, "the knee centre moves at most a femur length (" + formatDouble(femur) +
                            " m) per radian"};
  }
  const double peak = *std::max_element(r.envelope.torque.begin(), r.envelope.torque.end());
  return {peak, std::numeric_limits<double>::infinity(),
          "the peak envelope torque (" + formatDouble(peak) +
              " N·m) twists the joint at most one radian"};
}

}  // namespace gaitopt
