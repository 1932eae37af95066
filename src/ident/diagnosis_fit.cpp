// The fit engine of the model diagnosis: residual layouts, noise weights, the linearised
// candidates and their Gauss–Newton fits, and the χ² statistics of the tests.
#include "gaitopt/ident/diagnosis_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <thread>

namespace gaitopt::diagnosis {

double chi2Survival(double x, int k) {
  if (x <= 0.0) return 1.0;
  const double h = 0.5 * x;
  const bool odd = k % 2 == 1;
  double sum = odd ? std::erfc(std::sqrt(h)) : 0.0;
  double term = odd ? std::exp(-h) * std::sqrt(h) / std::tgamma(1.5) : std::exp(-h);
  double order = odd ? 1.5 : 1.0;  // Γ(order) divides the next term
  for (int i = 0; i < k / 2; ++i, order += 1.0) {
    sum += term;
    term *= h / order;
  }
  return std::min(1.0, sum);
}

double chi2Quantile1(double tail) {
  double lo = 0.0, hi = 200.0;
  for (int i = 0; i < 100; ++i) (chi2Survival(0.5 * (lo + hi)) > tail ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

double effectValue(EffectKind kind, double deviation) {
  return effectInfo(kind).factor ? 1.0 + deviation : deviation;
}

std::vector<Entry> fitEntries(const PreparedData& p, const ResidualMatrix& r,
                              const std::vector<char>& rows, double edge_trim) {
  std::vector<Entry> out;
  for (int c = 0; c < kNumChannels; ++c)
    for (std::size_t s = 0; s < p.segments.size(); ++s) {
      const Segment& seg = p.segments[s];
      const bool ss = seg.phase == Phase::SingleSupport;
      if (ss == (c == kFoot2z)) continue;  // SS dynamics, DS closure
      for (std::size_t i = seg.begin; i < seg.end; ++i) {
        if (!rows[i] || !std::isfinite(r(i, c))) continue;
        const std::vector<double>& t = p.data.t;
        if (ss && (t[i] - t[seg.begin] < edge_trim || t[seg.end - 1] - t[i] < edge_trim)) continue;
        out.push_back({i, c, static_cast<int>(s)});
      }
    }
  return out;
}

double inflation(const std::vector<Entry>& entries, const Eigen::VectorXd& r) {
  const double r2 = r.squaredNorm();
  if (r2 <= 0.0) return 1.0;
  constexpr std::size_t kMaxLag = 150;
  std::array<double, kMaxLag + 1> num{};
  for (std::size_t a = 0; a < entries.size();) {  // runs of consecutive rows
    std::size_t b = a + 1;
    while (b < entries.size() && entries[b].channel == entries[a].channel &&
           entries[b].segment == entries[a].segment && entries[b].row == entries[b - 1].row + 1)
      ++b;
    for (std::size_t k = 1; k <= kMaxLag && k < b - a; ++k)
      num[k] += r.segment(a, b - a - k).dot(r.segment(a + k, b - a - k));
    a = b;
  }
  double phi = 1.0;
  for (std::size_t k = 1; k <= kMaxLag && num[k] > 0.0; ++k) phi += 2.0 * num[k] / r2;
  return phi;
}

void parallelFor(int n, const std::function<void(int)>& body) {
  const int workers = std::max(1u, std::min(2u, std::thread::hardware_concurrency()));
  std::atomic<int> next{0};
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w)
    pool.emplace_back([&] { for (int i; (i = next++) < n;) body(i); });
  for (int i; (i = next++) < n;) body(i);
  for (std::thread& t : pool) t.join();
}

std::array<double, kNumChannels> channelSigma(const Problem& pb, const ResidualMatrix& r) {
  std::array<double, kNumChannels> sum{}, n{}, sigma{};
  for (const Entry& e : pb.entries) {
    const double x = r(e.row, e.channel);
    if (!std::isfinite(x)) continue;
    sum[e.channel] += x * x;
    n[e.channel] += 1.0;
  }
  for (int c = 0; c < kNumChannels; ++c)
    sigma[c] = n[c] > 0.0 && sum[c] > 0.0 ? std::sqrt(sum[c] / n[c]) : 1.0;
  return sigma;
}

Eigen::VectorXd weightedVector(const std::vector<Entry>& entries, const Eigen::VectorXd& raw,
                               const std::array<double, kNumChannels>& sigma) {
  Eigen::VectorXd v(raw.size());
  for (Eigen::Index e = 0; e < raw.size(); ++e) v(e) = raw(e) / sigma[entries[e].channel];
  return v;
}

Eigen::VectorXd entryValues(const std::vector<Entry>& entries, const ResidualMatrix& r) {
  Eigen::VectorXd v(entries.size());
  for (std::size_t e = 0; e < entries.size(); ++e) {
    const double x = r(entries[e].row, entries[e].channel);
    v(e) = std::isfinite(x) ? x : 0.0;
  }
  return v;
}

Evaluation Context::evaluate(const std::vector<Effect>& effects) const {
  return evaluate(withEffects(fit.nominal, effects));
}

Evaluation Context::evaluate(const RobotParams& robot) const {
  const std::vector<char> all(fit.prepared.data.size(), 1);
  const ResidualMatrix r = residuals(fit.prepared, robot, fit.model_options, all);
  return {entryValues(fit.entries, r), entryValues(held.entries, r)};
}

Linearisation linearise(const Context& ctx, const std::vector<Effect>& candidates,
                        const Evaluation& r0) {
  Linearisation lin{r0, candidates, std::vector<Evaluation>(candidates.size())};
  parallelFor(static_cast<int>(candidates.size()), [&](int i) {
    Effect e = candidates[i];
    const double h = effectInfo(e.kind).step;
    e.value = effectValue(e.kind, h);
    const Evaluation r = ctx.evaluate({e});
    lin.columns[i] = {(r.fit - r0.fit) / h, (r.held - r0.held) / h};
  });
  return lin;
}

Fit chordFit(const Context& ctx, const Linearisation& lin, const std::vector<int>& which,
             const std::array<double, kNumChannels>& sigma, int iterations) {
  const int k = static_cast<int>(which.size());
  const std::vector<Entry>& entries = ctx.fit.entries;
  Eigen::MatrixXd J(entries.size(), k);
  for (int i = 0; i < k; ++i) J.col(i) = weightedVector(entries, lin.columns[which[i]].fit, sigma);
  Fit f;
  f.JtJ = J.transpose() * J;
  const Eigen::LDLT<Eigen::MatrixXd> solver(f.JtJ);
  Eigen::VectorXd p = Eigen::VectorXd::Zero(k);
  Eigen::VectorXd r = weightedVector(entries, lin.r0.fit, sigma);
  f.r = lin.r0;
  const auto effectsAt = [&](const Eigen::VectorXd& x) {
    std::vector<Effect> e;
    for (int i = 0; i < k; ++i) {
      Effect c = lin.candidates[which[i]];
      c.value = effectValue(c.kind, x(i));
      e.push_back(c);
    }
    return e;
  };
  const bool linear = std::all_of(which.begin(), which.end(),
                                  [&](int c) { return effectInfo(lin.candidates[c].kind).linear; });
  if (linear && iterations > 0) {  // the linearisation is exact: no model evaluation needed
    p = solver.solve(-J.transpose() * r);
    for (int i = 0; i < k; ++i) {
      f.r.fit += lin.columns[which[i]].fit * p(i);
      f.r.held += lin.columns[which[i]].held * p(i);
    }
    iterations = 0;
  }
  for (int it = 0; it < iterations; ++it) {
    const Eigen::VectorXd delta = solver.solve(-J.transpose() * r);
    const Evaluation trial = ctx.evaluate(effectsAt(p + delta));
    const Eigen::VectorXd rt = weightedVector(entries, trial.fit, sigma);
    if (it > 0 && rt.squaredNorm() >= r.squaredNorm()) break;
    p += delta;
    r = rt;
    f.r = trial;
    double change = 0.0;
    for (int i = 0; i < k; ++i)
      change = std::max(change, std::abs(delta(i)) / effectInfo(lin.candidates[which[i]].kind).step);
    if (change < 1e-3) break;
  }
  f.effects = effectsAt(p);
  return f;
}

Fit gaussNewton(const Context& ctx, Fit f, const std::array<double, kNumChannels>& sigma,
                int iterations) {
  const int k = static_cast<int>(f.effects.size());
  const std::vector<Entry>& entries = ctx.fit.entries;
  if (std::all_of(f.effects.begin(), f.effects.end(),
                  [](const Effect& e) { return effectInfo(e.kind).linear; })) {
    // Exact in one weighted LS step from the columns (they do not depend on the point).
    return f;
  }
  Eigen::VectorXd r = weightedVector(entries, f.r.fit, sigma);
  for (int it = 0; it < iterations; ++it) {
    Eigen::MatrixXd J(entries.size(), k);
    for (int i = 0; i < k; ++i) {
      std::vector<Effect> e = f.effects;
      const EffectInfo& info = effectInfo(e[i].kind);
      const double h = 0.1 * info.step;
      e[i].value += h;
      J.col(i) = (weightedVector(entries, ctx.evaluate(e).fit, sigma) - r) / h;
    }
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    const Eigen::VectorXd delta = JtJ.ldlt().solve(-J.transpose() * r);
    std::vector<Effect> e = f.effects;
    for (int i = 0; i < k; ++i) e[i].value += delta(i);
    const Evaluation trial = ctx.evaluate(e);
    const Eigen::VectorXd rt = weightedVector(entries, trial.fit, sigma);
    if (rt.squaredNorm() >= r.squaredNorm()) break;
    f = {e, trial, JtJ};
    r = rt;
  }
  return f;
}

ResidualMatrix fitMatrix(std::size_t rows, const std::vector<Entry>& entries,
                         const Eigen::VectorXd& values) {
  ResidualMatrix m = ResidualMatrix::Constant(rows, kNumChannels, kNaN);
  for (std::size_t e = 0; e < entries.size(); ++e) m(entries[e].row, entries[e].channel) = values(e);
  return m;
}

double signalInflation(const std::vector<Entry>& entries, const Eigen::VectorXd& base,
                       const Eigen::VectorXd& r) {
  std::array<std::vector<Entry>, kNumChannels> e;
  std::array<std::vector<double>, kNumChannels> v;
  std::array<double, kNumChannels> drop{};
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const int c = entries[i].channel;
    e[c].push_back(entries[i]);
    v[c].push_back(r(i));
    drop[c] += base(i) * base(i) - r(i) * r(i);
  }
  double num = 0.0, den = 0.0;
  for (int c = 0; c < kNumChannels; ++c) {
    if (e[c].empty() || drop[c] <= 0.0) continue;
    num += drop[c] * inflation(e[c], Eigen::Map<const Eigen::VectorXd>(v[c].data(), v[c].size()));
    den += drop[c];
  }
  return den > 0.0 ? num / den : inflation(entries, r);
}

double bestChannelGain(const std::vector<Entry>& entries, const Eigen::VectorXd& before,
                       const Eigen::VectorXd& after) {
  std::array<double, kNumChannels> b{}, a{};
  for (std::size_t e = 0; e < entries.size(); ++e) {
    b[entries[e].channel] += before(e) * before(e);
    a[entries[e].channel] += after(e) * after(e);
  }
  double best = -1e300;
  for (int c = 0; c < kNumChannels; ++c)
    if (b[c] > 0.0) best = std::max(best, 100.0 * (1.0 - std::sqrt(a[c] / b[c])));
  return best;
}

std::pair<std::vector<int>, double> effectChannels(const std::vector<Entry>& entries,
                                                   const Eigen::VectorXd& before,
                                                   const Eigen::VectorXd& after) {
  std::array<double, kNumChannels> change{}, b{}, a{};
  for (std::size_t e = 0; e < entries.size(); ++e) {
    const int c = entries[e].channel;
    change[c] += (before(e) - after(e)) * (before(e) - after(e));
    b[c] += before(e) * before(e);
    a[c] += after(e) * after(e);
  }
  std::vector<int> order(kNumChannels);
  for (int c = 0; c < kNumChannels; ++c) order[c] = c;
  std::sort(order.begin(), order.end(), [&](int x, int y) { return change[x] > change[y]; });
  const double total = std::accumulate(change.begin(), change.end(), 0.0);
  std::vector<int> channels;
  double carried = 0.0, sb = 0.0, sa = 0.0;
  for (int c : order) {
    if (total <= 0.0 || carried >= 0.9 * total) break;
    channels.push_back(c);
    carried += change[c];
    sb += b[c];
    sa += a[c];
  }
  std::sort(channels.begin(), channels.end());
  return {channels, sb > 0.0 ? 100.0 * (1.0 - std::sqrt(sa / sb)) : 0.0};
}

std::vector<int> actingChannels(const std::vector<Entry>& entries, const Eigen::VectorXd& before,
                                const Eigen::VectorXd& after, double share) {
  std::array<double, kNumChannels> change{}, b{};
  for (std::size_t e = 0; e < entries.size(); ++e) {
    change[entries[e].channel] += (after(e) - before(e)) * (after(e) - before(e));
    b[entries[e].channel] += before(e) * before(e);
  }
  std::vector<int> channels;
  for (int c = 0; c < kNumChannels; ++c)
    if (b[c] > 0.0 && change[c] >= share * share * b[c]) channels.push_back(c);
  return channels;
}

}  // namespace gaitopt::diagnosis
