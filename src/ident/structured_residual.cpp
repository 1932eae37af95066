// Cross-step prediction test of the residual structure left by a model.
#include "gaitopt/ident/structured_residual.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace gaitopt::diagnosis {

namespace {

constexpr int kMinEntries = 30;
constexpr int kNumSignals = 5;  // the signatures other than `none`, in Signature order

// Per sample: α and the joint-side motor angles, their rates and accelerations; the measured
// motor torques and their rates.
struct SignatureData {
  std::vector<Vec5> angle, velocity, acceleration;
  std::vector<Vec4> torque, torque_rate;
  bool has_torque = false;

  explicit SignatureData(const PreparedData& p) : has_torque(p.data.has_torque) {
    const Kinematics& k = p.measured;
    const auto joints = [](const Vec5& q) {
      Vec5 v;
      v << q(0), motorAngles(q);
      return v;
    };
    for (std::size_t i = 0; i < p.data.size(); ++i) {
      angle.push_back(joints(k.q[i]));
      velocity.push_back(joints(k.qd[i]));
      acceleration.push_back(joints(k.qdd[i]));
    }
    if (!has_torque) return;
    torque = p.data.gamma;
    torque_rate.assign(p.data.size(), Vec4::Zero());
    for (int j = 0; j < 4; ++j) {
      std::vector<double> g(p.data.size());
      for (std::size_t i = 0; i < g.size(); ++i) g[i] = p.data.gamma[i](j);
      const SmoothedSignal s = p.differentiator.apply(g);
      for (std::size_t i = 0; i < g.size(); ++i) torque_rate[i](j) = s.first[i];
    }
  }

  bool available(int signal) const { return signal < 3 || has_torque; }

  // The raw measurement noise of each channel: the robust scatter of the measured signal's
  // second differences — torque of the joint, reaction component, centre of pressure; for the channels computed from
  // the angles alone, the angle scatter times the leg length (rear-foot height) or times the
  // robot's weight and leg length (alpha row, the moment of that angle error).
  std::array<double, kNumChannels> floor{};
  void setFloors(const PreparedData& p, const RobotParams& robot) {
    const MeasuredData& d = p.data;
    const double angle = angleScatter(p);
    const double leg = std::min(robot.l1 + robot.l2, robot.l4 + robot.l5);
    double mass = robot.hip_payload + (robot.bar.present ? robot.bar.equivalent_mass : 0.0);
    for (double m : robot.mass) mass += m;
    floor[kAlphaRow] = angle * mass * robot.gravity * leg;
    floor[kFoot2z] = angle * leg;
    // White noise of σ gives second differences of σ √6; a signal sampled at 500 Hz hardly any.
    const auto scatter = [&](const auto& x, int k) {
      std::vector<double> v;
      for (const Segment& seg : p.segments)
        for (std::size_t i = seg.begin + 1; i + 1 < seg.end; ++i)
          v.push_back(x[i + 1][k] - 2.0 * x[i][k] + x[i - 1][k]);
      return robustScatter(v) / std::sqrt(6.0);
    };
    if (d.has_torque) {
      double torque = 0.0;  // one level for the four joints: the motors' sensors are alike
      for (int j = 0; j < 4; ++j) torque += scatter(d.gamma, j) / 4.0;
      for (int c = kGammaKneeLeft; c <= kGammaKneeRight; ++c) floor[c] = torque;
    }
    if (d.has_reactions)
      for (int k = 0; k < 4; ++k) floor[kR1x + k] = scatter(d.reactions, k);
    if (d.has_cop) floor[kCopX] = scatter(d.cop, 0);
  }

  // The variables of `signal` at sample i for `channel`: the joint's own for a joint-torque
  // channel (its motor changes with the stance); else α's, or the four motor torques.
  Eigen::VectorXd variables(int signal, std::size_t i, int channel, Stance stance) const {
    const bool joint = channel >= kGammaKneeLeft && channel <= kGammaKneeRight;
    const int motor = joint ? physicalJointOfMotor(channel - kGammaKneeLeft, stance) : -1;
    if (signal >= 3) {
      const Vec4& v = signal == 3 ? torque[i] : torque_rate[i];
      return joint ? Eigen::VectorXd::Constant(1, v(motor)) : Eigen::VectorXd(v);
    }
    // Other channels: α alone. In single support every joint follows α (the gait's virtual
    // constraints), so combinations of the five smoothed coordinates isolate their smoothing
    // noise — the very noise of the residual, which they would then "predict" across steps.
    const Vec5& v = signal == 0 ? angle[i] : signal == 1 ? velocity[i] : acceleration[i];
    return Eigen::VectorXd::Constant(1, v(joint ? motor + 1 : 0));
  }
};

struct Range {
  std::size_t begin = 0, size = 0;
};

// The contiguous run of `channel` in `entries` (fitEntries orders them by channel).
Range channelRange(const std::vector<Entry>& entries, int channel) {
  Range r;
  while (r.begin < entries.size() && entries[r.begin].channel != channel) ++r.begin;
  while (r.begin + r.size < entries.size() && entries[r.begin + r.size].channel == channel) ++r.size;
  return r;
}

// Standardised polynomial columns (powers 1..degree) of `signal`'s variables on the fit and
// held-out entries of one channel, scaled by the fit entries' mean and spread.
std::pair<Eigen::MatrixXd, Eigen::MatrixXd> signalColumns(const SignatureData& sd, const Context& ctx,
                                                          const Range& fr, const Range& hr,
                                                          int channel, int signal) {
  const auto raw = [&](const Problem& pb, const Range& r) {
    Eigen::MatrixXd v;
    for (std::size_t e = 0; e < r.size; ++e) {
      const std::size_t i = pb.entries[r.begin + e].row;
      const Eigen::VectorXd x = sd.variables(signal, i, channel, pb.prepared.data.stance[i]);
      if (v.size() == 0) v.resize(r.size, x.size());
      v.row(e) = x.transpose();
    }
    return v;
  };
  Eigen::MatrixXd f = raw(ctx.fit, fr), h = raw(ctx.held, hr);
  const Eigen::RowVectorXd mean = f.colwise().mean();
  const Eigen::RowVectorXd spread =
      ((f.rowwise() - mean).colwise().squaredNorm() / f.rows()).cwiseSqrt().cwiseMax(1e-12);
  const int degree = f.cols() == 1 ? 3 : 2;
  const auto powers = [&](const Eigen::MatrixXd& v) {
    const Eigen::MatrixXd z = (v.rowwise() - mean).array().rowwise() / spread.array();
    Eigen::MatrixXd out(z.rows(), z.cols() * degree);
    for (int d = 0; d < degree; ++d) out.middleCols(d * z.cols(), z.cols()) = z.array().pow(d + 1).matrix();
    return out;
  };
  return {powers(f), powers(h)};
}

// The gait-phase block: in single support the state is a function of α (the gait's virtual
// constraints) up to the step-to-step variation, so any residual that repeats from step to step
// is a function of α — piecewise-linear hat functions over α's range, one set per stance leg
// (the physical joints swap roles with it). It catches what the named signatures cannot
// express (e.g. the second derivative of a torque).
std::pair<Eigen::MatrixXd, Eigen::MatrixXd> phaseColumns(const SignatureData& sd, const Context& ctx,
                                                         const Range& fr, const Range& hr) {
  constexpr int kKnots = 10;
  std::array<double, 2> lo{1e300, 1e300}, hi{-1e300, -1e300};
  for (std::size_t e = 0; e < fr.size; ++e) {
    const std::size_t i = ctx.fit.entries[fr.begin + e].row;
    const int st = static_cast<int>(ctx.fit.prepared.data.stance[i]);
    lo[st] = std::min(lo[st], sd.angle[i](0));
    hi[st] = std::max(hi[st], sd.angle[i](0));
  }
  const auto hats = [&](const Problem& pb, const Range& r) {
    Eigen::MatrixXd x = Eigen::MatrixXd::Zero(r.size, 2 * kKnots);
    for (std::size_t e = 0; e < r.size; ++e) {
      const std::size_t i = pb.entries[r.begin + e].row;
      const int st = static_cast<int>(pb.prepared.data.stance[i]);
      if (!(hi[st] > lo[st])) continue;
      const double u = std::clamp((sd.angle[i](0) - lo[st]) / (hi[st] - lo[st]), 0.0, 1.0) * (kKnots - 1);
      const int k = std::min(kKnots - 2, static_cast<int>(u));
      x(e, st * kKnots + k) = k + 1 - u;
      x(e, st * kKnots + k + 1) = u - k;
    }
    return x;
  };
  return {hats(ctx.fit, fr), hats(ctx.held, hr)};
}

// RMS of the measured signal of a torque or reaction channel on `pb`'s entries of `r` (0 for
// the channels the model predicts as zero: alpha row, rear-foot height).
double signalRms(const Problem& pb, const Range& r, int channel) {
  const MeasuredData& d = pb.prepared.data;
  double sum = 0.0;
  for (std::size_t e = 0; e < r.size; ++e) {
    const std::size_t i = pb.entries[r.begin + e].row;
    double x = 0.0;
    if (channel >= kGammaKneeLeft && channel <= kGammaKneeRight && d.has_torque)
      x = d.gamma[i](physicalJointOfMotor(channel - kGammaKneeLeft, d.stance[i]));
    else if (channel >= kR1x && channel <= kR2z && d.has_reactions)
      x = d.reactions[i](channel - kR1x);
    sum += x * x;
  }
  return std::sqrt(sum / std::max<std::size_t>(1, r.size));
}

// Held-out prediction of the least-squares fit of r_fit on [1, columns].
// A small ridge (1e-6 of the largest diagonal of AᵀA) keeps the solution bounded where columns
// are collinear (the two stances' hat functions sum to the constant).
Eigen::VectorXd predict(const Eigen::MatrixXd& xf, const Eigen::MatrixXd& xh, const Eigen::VectorXd& rf) {
  Eigen::MatrixXd af(xf.rows(), xf.cols() + 1), ah(xh.rows(), xh.cols() + 1);
  af << Eigen::VectorXd::Ones(xf.rows()), xf;
  ah << Eigen::VectorXd::Ones(xh.rows()), xh;
  Eigen::MatrixXd normal = af.transpose() * af;
  normal.diagonal().array() += 1e-6 * normal.diagonal().maxCoeff();
  return ah * normal.ldlt().solve(af.transpose() * rf);
}

double rms(const Eigen::VectorXd& v) { return std::sqrt(v.squaredNorm() / std::max<Eigen::Index>(1, v.size())); }

ChannelTest testChannel(const SignatureData& sd, const Context& ctx, const Evaluation& r,
                        const Range& fr, const Range& hr, int channel, const DiagnoseOptions& o,
                        const StructureThreshold& th) {
  const Eigen::VectorXd rf = r.fit.segment(fr.begin, fr.size), rh = r.held.segment(hr.begin, hr.size);
  std::vector<std::pair<Eigen::MatrixXd, Eigen::MatrixXd>> cols;
  Eigen::Index width = 0;
  for (int s = 0; s < kNumSignals; ++s) {
    if (sd.available(s)) cols.push_back(signalColumns(sd, ctx, fr, hr, channel, s));
    else cols.push_back({Eigen::MatrixXd(fr.size, 0), Eigen::MatrixXd(hr.size, 0)});
    width += cols.back().first.cols();
  }
  cols.push_back(phaseColumns(sd, ctx, fr, hr));
  width += cols.back().first.cols();
  Eigen::MatrixXd xf(fr.size, width), xh(hr.size, width);
  for (std::size_t c = 0, s = 0; s < cols.size(); c += cols[s].first.cols(), ++s) {
    xf.middleCols(c, cols[s].first.cols()) = cols[s].first;
    xh.middleCols(c, cols[s].second.cols()) = cols[s].second;
  }
  const Eigen::VectorXd y = predict(xf, xh, rf);
  const Eigen::VectorXd noise = rh - y;
  ChannelTest t;
  t.channel = channel;
  t.heldout_rms = rms(rh);
  t.noise_rms = rms(noise);
  t.gain_pct = t.heldout_rms > 0.0 ? 100.0 * (1.0 - t.noise_rms / t.heldout_rms) : 0.0;
  const std::vector<Entry> held(ctx.held.entries.begin() + hr.begin,
                                ctx.held.entries.begin() + hr.begin + hr.size);
  const double variance = inflation(held, noise) * t.noise_rms * t.noise_rms * y.squaredNorm();
  t.p_value = variance > 0.0 ? 0.5 * std::erfc(rh.dot(y) / std::sqrt(2.0 * variance)) : 1.0;
  const double structure = std::sqrt(std::max(0.0, t.heldout_rms * t.heldout_rms - t.noise_rms * t.noise_rms));
  t.structured = t.p_value < o.significance / kNumChannels && t.gain_pct >= th.min_gain &&
                 structure > std::max(sd.floor[channel], th.signal_share * signalRms(ctx.held, hr, channel));
  if (!t.structured) return t;  // the signature only names a structure
  double best = (rh - predict(xf.leftCols(0), xh.leftCols(0), rf)).squaredNorm();
  for (int s = 0; s < kNumSignals; ++s) {
    if (cols[s].first.cols() == 0) continue;
    const double rss = (rh - predict(cols[s].first, cols[s].second, rf)).squaredNorm();
    if (rss < best) {
      best = rss;
      t.signature = static_cast<Signature>(s);
    }
  }
  return t;
}

}  // namespace

double robustScatter(std::vector<double> deviations) {
  if (deviations.empty()) return 0.0;
  for (double& x : deviations) x = std::abs(x);
  std::nth_element(deviations.begin(), deviations.begin() + deviations.size() / 2, deviations.end());
  return 1.4826 * deviations[deviations.size() / 2];
}

double angleScatter(const PreparedData& p) {
  std::vector<double> deviations;
  for (std::size_t i = 0; i < p.data.size(); ++i)
    for (int k = 0; k < 5; ++k) deviations.push_back(p.data.q[i](k) - p.measured.q[i](k));
  return robustScatter(deviations);
}

std::vector<ChannelTest> testChannels(const Context& ctx, const Evaluation& r, const DiagnoseOptions& o,
                                      const StructureThreshold& th) {
  SignatureData sd(ctx.fit.prepared);
  sd.setFloors(ctx.fit.prepared, ctx.fit.nominal);
  std::vector<ChannelTest> out;
  for (int c = 0; c < kNumChannels; ++c) {
    const Range fr = channelRange(ctx.fit.entries, c), hr = channelRange(ctx.held.entries, c);
    if (fr.size < kMinEntries || hr.size < kMinEntries) continue;
    out.push_back(testChannel(sd, ctx, r, fr, hr, c, o, th));
  }
  return out;
}

}  // namespace gaitopt::diagnosis
