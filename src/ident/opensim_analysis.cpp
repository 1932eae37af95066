#include "gaitopt/ident/opensim_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "gaitopt/model/dynamics_floating.hpp"

namespace gaitopt {

namespace {

using Vec7 = Vector7<double>;

// The floating model (1.1) at one sample, with the reactions of the legs in contact applied at
// their centres of pressure: a force at the CoP of the lumped tibia (shank + foot) is the force
// at the model's foot point plus the moment (CoP − foot) × R on that tibia.
struct FloatingSample {
  Vec7 lhs;           // A Ẍ + C + G
  Vec7 tau;           // lhs − generalised reaction forces = D_Γ Γ
  Vec2 foot[2];       // leg 1, leg 2 foot points (ankles)
  Vec2 trunk_com;
  double cop_moment[2] = {0, 0};  // (CoP − foot) × R about each foot [N·m]
};

FloatingSample floatingSample(const ImportedTrial& trial, const Model& model, Eigen::Index k) {
  const double s3 = model.com_offset(2);
  const double psi = trial.trunk.v(k), w = trial.trunk.d(k), a = trial.trunk.dd(k);
  const Vec2 u(-std::sin(psi), std::cos(psi)), u_dot(-std::cos(psi), -std::sin(psi));
  Vec7 X, Xd, Xdd;
  const Vec2 com = Vec2(trial.hip_x.v(k), trial.hip_z.v(k)) + s3 * u;
  X << trial.q.row(k).transpose(), com;
  Xd << trial.qd.row(k).transpose(), Vec2(trial.hip_x.d(k), trial.hip_z.d(k)) + s3 * w * u_dot;
  Xdd << trial.qdd.row(k).transpose(),
      Vec2(trial.hip_x.dd(k), trial.hip_z.dd(k)) + s3 * (a * u_dot - w * w * u);
  const FloatingTerms<double> t = floatingTerms(model, X, Xd);
  FloatingSample f;
  f.trunk_com = com;
  f.lhs = t.A * Xdd + t.C + t.G;
  f.tau = f.lhs;
  const ChainState<double> st = chainState<double>(model, X.head<5>(), Xd.head<5>());
  const BodySide sides[2] = {trial.leg1[k], otherSide(trial.leg1[k])};
  const Vec5* feet[2] = {&model.floating.foot1, &model.floating.foot2};
  const Matrix27<double>* D[2] = {&t.D1, &t.D2};
  const int tibia[2] = {0, 4};  // θ1, θ5: the bodies that carry the feet
  for (int i = 0; i < 2; ++i) {
    f.foot[i] = com + chainPoint(*feet[i], st);
    const ImportedLeg& leg = trial.legs[int(sides[i])];
    if (!leg.contact[k]) continue;
    const Vec2 R = leg.force.row(k).transpose();
    const Vec2 r = leg.cop.row(k).transpose() - f.foot[i];
    f.cop_moment[i] = r.x() * R.y() - r.y() * R.x();
    f.tau -= D[i]->transpose() * R;
    f.tau.head<5>() -= f.cop_moment[i] * model.theta_map.row(tibia[i]).transpose();
  }
  return f;
}

// Γ from D_Γ Γ = τ projected on virtual motions that move only the links distal to each joint
// with the trunk fixed: tibia 1 about knee 1 (α +1, δ1 −1), leg 1 about the hip (α +1, δ2 +1,
// δ3 −1), leg 2 about the hip (δ3), tibia 2 about knee 2 (δ4); see D_Γ (1.19).
Vec4 distalTorques(const Vec7& tau) {
  return Vec4(tau(1) - tau(0), -(tau(0) + tau(2) - tau(3)), -tau(3), tau(4));
}

double rms(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return v.empty() ? 0.0 : std::sqrt(s / double(v.size()));
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const Eigen::Map<const Eigen::VectorXd> x(a.data(), Eigen::Index(a.size())), y(b.data(), Eigen::Index(b.size()));
  const Eigen::VectorXd dx = x.array() - x.mean(), dy = y.array() - y.mean();
  return dx.dot(dy) / std::sqrt(dx.squaredNorm() * dy.squaredNorm());
}

bool inner(const ImportedTrial& trial, Eigen::Index k, double margin) {
  return trial.t(k) >= trial.t(0) + margin && trial.t(k) <= trial.t(trial.t.size() - 1) - margin;
}

// Weighted centring of one stance: (α − ᾱ, cop − c̄) with force weights.
void centred(const StanceSamples& s, Eigen::VectorXd& a, Eigen::VectorXd& c) {
  const double W = s.weight.sum();
  a = s.shank.array() - s.weight.dot(s.shank) / W;
  c = s.cop_x.array() - s.weight.dot(s.cop_x) / W;
}

std::vector<StanceSamples> ofSide(const std::vector<StanceSamples>& all, BodySide side) {
  std::vector<StanceSamples> out;
  std::copy_if(all.begin(), all.end(), std::back_inserter(out),
               [side](const StanceSamples& s) { return s.side == side; });
  return out;
}

RockerFootReport rockerReport(const ImportedTrial& trial) {
  const std::vector<StanceSamples> all = importedStances(trial);
  const std::vector<StanceSamples> right = ofSide(all, BodySide::Right), left = ofSide(all, BodySide::Left);
  RockerFootReport r;
  r.stances_right = int(right.size());
  r.stances_left = int(left.size());
  r.radius_right = fitRockerRadius(right);
  r.radius_left = fitRockerRadius(left);
  r.radius_all = fitRockerRadius(all);
  // Pooled held-out RMS: weights of the two test sets add, so square-average by sample count.
  const double nr = double(right.size()), nl = double(left.size());
  const auto pooled = [&](double on_left, double on_right) {
    return std::sqrt((nl * on_left * on_left + nr * on_right * on_right) / std::max(1.0, nl + nr));
  };
  r.holdout_rms_point = pooled(rockerCopRms(left, 0.0), rockerCopRms(right, 0.0));
  r.holdout_rms_rocker = pooled(rockerCopRms(left, r.radius_right), rockerCopRms(right, r.radius_left));
  r.holdout_gain_pct = 100.0 * (1.0 - r.holdout_rms_rocker / r.holdout_rms_point);
  r.leg_length = trial.hip_z.v.maxCoeff() - trial.ground_z;
  r.literature_radius = 0.3 * r.leg_length;
  return r;
}

std::vector<JointComparison> compareWithReference(const ImportedTrial& trial,
                                                  const Eigen::MatrixX4d& torque,
                                                  const OpenSimTable& id, double margin) {
  // OpenSim's coordinates grow opposite to δ (δ1 = −knee − π, δ2 = hip − π, …, (1.19)), so
  // each OpenSim moment is −Γ of the joint's motor; a knee_angle positive in flexion grows
  // with δ1, and its moment is +Γ.
  const char* names[4] = {"hip_right", "knee_right", "hip_left", "knee_left"};
  const char* columns[4] = {"hip_flexion_r_moment", "knee_angle_r_moment", "hip_flexion_l_moment",
                            "knee_angle_l_moment"};
  std::vector<JointComparison> out;
  for (int j = 0; j < 4; ++j) {
    const BodySide side = j < 2 ? BodySide::Right : BodySide::Left;
    const bool knee = j % 2 == 1;
    const Eigen::VectorXd ref = id.column(columns[j]);
    std::vector<double> ours, theirs, diff;
    for (Eigen::Index r = 0; r < id.rows(); ++r) {
      const double tr = id.values(r, 0);
      const Eigen::Index k = std::lower_bound(trial.t.data(), trial.t.data() + trial.t.size(), tr) - trial.t.data();
      const Eigen::Index kk = (k > 0 && (k == trial.t.size() || tr - trial.t(k - 1) < trial.t(k) - tr)) ? k - 1 : k;
      if (std::abs(trial.t(kk) - tr) > 1e-3 || !inner(trial, kk, margin)) continue;
      const bool is_leg1 = trial.leg1[kk] == side;
      const int motor = knee ? (is_leg1 ? 0 : 3) : (is_leg1 ? 1 : 2);
      const bool flexion_positive = knee && trial.conventions.knee == KneeFlexion::Positive;
      ours.push_back((flexion_positive ? 1.0 : -1.0) * torque(kk, motor));
      theirs.push_back(ref(r));
      diff.push_back(ours.back() - theirs.back());
    }
    out.push_back({names[j], rms(diff), rms(theirs), correlation(ours, theirs), int(ours.size())});
  }
  return out;
}

// Per step (leg-1 period), the offset c of the rocker CoP c − r α with r the radius fitted on
// the OTHER leg (held out), and that r: the contact point a rocker foot would have.
std::map<int, std::pair<double, double>> rockerPlacement(const ImportedTrial& trial,
                                                         const RockerFootReport& r) {
  std::map<int, std::pair<double, double>> sum;  // step → (Σ w (cop + r α), Σ w)
  for (Eigen::Index k = 0; k < trial.t.size(); ++k) {
    const ImportedLeg& leg = trial.legs[int(trial.leg1[k])];
    if (!leg.contact[k]) continue;
    const double radius = trial.leg1[k] == BodySide::Right ? r.radius_left : r.radius_right;
    const double w = leg.force(k, 1);
    sum[trial.step[k]].first += w * (leg.cop(k, 0) + radius * leg.shank.v(k));
    sum[trial.step[k]].second += w;
  }
  std::map<int, std::pair<double, double>> out;
  for (const auto& [step, s] : sum) out[step] = {s.first / s.second, 0.0};
  for (Eigen::Index k = 0; k < trial.t.size(); ++k)
    out[trial.step[k]].second = trial.leg1[k] == BodySide::Right ? r.radius_left : r.radius_right;
  return out;
}

}  // namespace

double fitRockerRadius(const std::vector<StanceSamples>& stances) {
  double num = 0, den = 0;
  for (const StanceSamples& s : stances) {
    Eigen::VectorXd a, c;
    centred(s, a, c);
    num += (s.weight.array() * a.array() * c.array()).sum();
    den += (s.weight.array() * a.array().square()).sum();
  }
  return den > 0 ? -num / den : 0.0;
}

double rockerCopRms(const std::vector<StanceSamples>& stances, double radius) {
  double sum = 0, weight = 0;
  for (const StanceSamples& s : stances) {
    Eigen::VectorXd a, c;
    centred(s, a, c);
    sum += (s.weight.array() * (c + radius * a).array().square()).sum();
    weight += s.weight.sum();
  }
  return weight > 0 ? std::sqrt(sum / weight) : 0.0;
}

std::vector<StanceSamples> importedStances(const ImportedTrial& trial, int min_samples) {
  std::vector<StanceSamples> out;
  const Eigen::Index n = trial.t.size();
  for (Eigen::Index k = 0; k < n;) {
    Eigen::Index end = k;
    while (end < n && trial.step[end] == trial.step[k]) ++end;
    const BodySide side = trial.leg1[k];
    const ImportedLeg& leg = trial.legs[int(side)];
    std::vector<Eigen::Index> rows;
    for (Eigen::Index j = k; j < end; ++j)
      if (leg.contact[j]) rows.push_back(j);
    if (int(rows.size()) >= min_samples) {
      StanceSamples s;
      s.side = side;
      const Eigen::Index m = Eigen::Index(rows.size());
      s.shank.resize(m);
      s.cop_x.resize(m);
      s.weight.resize(m);
      for (Eigen::Index i = 0; i < m; ++i) {
        s.shank(i) = leg.shank.v(rows[i]);
        s.cop_x(i) = leg.cop(rows[i], 0);
        s.weight(i) = leg.force(rows[i], 1);
      }
      out.push_back(std::move(s));
    }
    k = end;
  }
  return out;
}

Eigen::MatrixX4d importedJointTorques(const ImportedTrial& trial, const Model& model) {
  Eigen::MatrixX4d torque(trial.t.size(), 4);
  for (Eigen::Index k = 0; k < trial.t.size(); ++k)
    torque.row(k) = distalTorques(floatingSample(trial, model, k).tau).transpose();
  return torque;
}

OpenSimAnalysis analyseImportedTrial(const ImportedTrial& trial, const Model& model,
                                     const OpenSimTable* reference_id) {
  OpenSimAnalysis a;
  a.stances = importedStances(trial);
  a.rocker = rockerReport(trial);
  const auto placement = rockerPlacement(trial, a.rocker);
  Eigen::MatrixX4d torque(trial.t.size(), 4);
  std::vector<double> residual, cop, diff, diff_rocker, fx, fz;
  for (Eigen::Index k = 0; k < trial.t.size(); ++k) {
    const FloatingSample f = floatingSample(trial, model, k);
    torque.row(k) = distalTorques(f.tau).transpose();
    if (!inner(trial, k, a.edge_margin)) continue;
    fx.push_back(f.tau(5));
    fz.push_back(f.tau(6));
    if (trial.double_support[k]) continue;
    // Rigid rotation about foot 1 (α +1, trunk CoM turning about the foot): the moment about
    // the point foot that gravity and inertia need from the ground.
    Vec7 v = Vec7::Zero();
    v(0) = 1.0;
    v(5) = -(f.trunk_com.y() - f.foot[0].y());
    v(6) = f.trunk_com.x() - f.foot[0].x();
    residual.push_back(v.dot(f.lhs));
    cop.push_back(f.cop_moment[0]);
    diff.push_back(residual.back() - cop.back());
    const auto [offset, radius] = placement.at(trial.step[k]);
    const ImportedLeg& leg = trial.legs[int(trial.leg1[k])];
    const Vec2 arm(offset - radius * leg.shank.v(k) - f.foot[0].x(), leg.cop(k, 1) - f.foot[0].y());
    diff_rocker.push_back(residual.back() - (arm.x() * leg.force(k, 1) - arm.y() * leg.force(k, 0)));
  }
  a.alpha_residual_rms = rms(residual);
  a.cop_moment_rms = rms(cop);
  a.alpha_minus_cop_rms = rms(diff);
  a.alpha_minus_rocker_rms = rms(diff_rocker);
  a.alpha_cop_correlation = correlation(residual, cop);
  a.single_support_samples = int(residual.size());
  a.force_residual_rms_x = rms(fx);
  a.force_residual_rms_z = rms(fz);
  if (reference_id) a.joints = compareWithReference(trial, torque, *reference_id, a.edge_margin);
  return a;
}

}  // namespace gaitopt
