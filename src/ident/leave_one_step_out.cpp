// Leave-one-step-out held-out gain and its bootstrap interval over the steps.
#include "gaitopt/ident/leave_one_step_out.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>

namespace gaitopt::diagnosis {

namespace {

constexpr int kResamples = 2000;

Eigen::VectorXd joined(const Evaluation& e) {
  Eigen::VectorXd v(e.fit.size() + e.held.size());
  v << e.fit, e.held;
  return v;
}

}  // namespace

Eigen::VectorXd LeaveOneStepOut::weighted(const Evaluation& e) const {
  return weightedVector(entries_, joined(e), sigma_);
}

LeaveOneStepOut::LeaveOneStepOut(const Context& ctx, const Fit& model,
                                 const std::array<double, kNumChannels>& sigma)
    : sigma_(sigma) {
  entries_ = ctx.fit.entries;
  entries_.insert(entries_.end(), ctx.held.entries.begin(), ctx.held.entries.end());
  std::map<long, int> ordinal;
  for (const Entry& e : entries_) ordinal.emplace(ctx.fit.prepared.data.step[e.row], 0);
  for (auto& [step, k] : ordinal) k = steps_++;
  for (const Entry& e : entries_) step_.push_back(ordinal.at(ctx.fit.prepared.data.step[e.row]));
  fitted_ = weighted(model.r);
  predicted_ = fitted_;
  const int k = static_cast<int>(model.effects.size());
  if (k == 0) return;
  Eigen::MatrixXd J(entries_.size(), k);
  for (int i = 0; i < k; ++i) {  // forward differences at the fitted values
    std::vector<Effect> e = model.effects;
    const double h = 0.1 * effectInfo(e[i].kind).step;
    e[i].value += h;
    J.col(i) = (weighted(ctx.evaluate(e)) - fitted_) / h;
  }
  std::vector<Eigen::MatrixXd> JtJ(steps_, Eigen::MatrixXd::Zero(k, k));
  std::vector<Eigen::VectorXd> Jtr(steps_, Eigen::VectorXd::Zero(k));
  for (std::size_t e = 0; e < entries_.size(); ++e) {
    JtJ[step_[e]] += J.row(e).transpose() * J.row(e);
    Jtr[step_[e]] += J.row(e).transpose() * fitted_(e);
  }
  Eigen::MatrixXd all_JtJ = Eigen::MatrixXd::Zero(k, k);
  Eigen::VectorXd all_Jtr = Eigen::VectorXd::Zero(k);
  for (int s = 0; s < steps_; ++s) {
    all_JtJ += JtJ[s];
    all_Jtr += Jtr[s];
  }
  std::vector<Eigen::VectorXd> delta(steps_);  // the parameter change fitted without step s
  for (int s = 0; s < steps_; ++s) delta[s] = (all_JtJ - JtJ[s]).ldlt().solve(-(all_Jtr - Jtr[s]));
  for (std::size_t e = 0; e < entries_.size(); ++e) predicted_(e) += J.row(e).dot(delta[step_[e]]);
}

GainInterval LeaveOneStepOut::gain(const Evaluation& base, const std::vector<int>& channels) const {
  const Eigen::VectorXd b = weighted(base);
  std::vector<double> before(steps_, 0.0), after(steps_, 0.0);
  for (std::size_t e = 0; e < entries_.size(); ++e) {
    if (std::find(channels.begin(), channels.end(), entries_[e].channel) == channels.end()) continue;
    before[step_[e]] += b(e) * b(e);
    after[step_[e]] += predicted_(e) * predicted_(e);
  }
  const auto pct = [](double sb, double sa) { return sb > 0.0 ? 100.0 * (1.0 - std::sqrt(sa / sb)) : kNaN; };
  GainInterval g;
  g.steps = steps_;
  double sb = 0.0, sa = 0.0;
  for (int s = 0; s < steps_; ++s) {
    sb += before[s];
    sa += after[s];
  }
  g.pct = pct(sb, sa);
  if (!std::isfinite(g.pct)) return g;
  std::mt19937_64 rng(1);  // seeded: the same data give the same interval
  std::uniform_int_distribution<int> draw(0, steps_ - 1);
  std::vector<double> resampled(kResamples);
  for (double& r : resampled) {
    double rb = 0.0, ra = 0.0;
    for (int s = 0; s < steps_; ++s) {
      const int k = draw(rng);
      rb += before[k];
      ra += after[k];
    }
    r = pct(rb, ra);
  }
  std::sort(resampled.begin(), resampled.end());
  g.low_pct = resampled[static_cast<std::size_t>(0.025 * kResamples)];
  g.high_pct = resampled[static_cast<std::size_t>(0.975 * kResamples) - 1];
  return g;
}

std::vector<int> LeaveOneStepOut::acting(const Evaluation& base, double share) const {
  return actingChannels(entries_, weighted(base), fitted_, share);
}

}  // namespace gaitopt::diagnosis
