#include "gaitopt/ident/diagnose.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <functional>
#include <thread>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace gaitopt {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// P(χ²_k > x) for an integer k ≥ 1, by the closed forms of the regularised upper incomplete
// gamma function at integer and half-integer order (term t_i = (x/2)^i / Γ(i + 1 or i + 3/2)).
double chi2Survival(double x, int k = 1) {
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

double chi2Quantile1(double tail) {  // x with P(χ²₁ > x) = tail, by bisection
  double lo = 0.0, hi = 200.0;
  for (int i = 0; i < 100; ++i) (chi2Survival(0.5 * (lo + hi)) > tail ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

double effectValue(EffectKind kind, double deviation) {
  return effectInfo(kind).factor ? 1.0 + deviation : deviation;
}

struct Entry {
  std::size_t row;
  int channel;
  int segment;
};

// One set of rows (fit or held-out steps) and its entries (row, channel), fixed from the
// nominal model so that every model's residual vector has the same layout.
struct Problem {
  const PreparedData& prepared;
  const RobotParams& nominal;
  const ModelOptions& model_options;
  std::vector<char> rows;
  std::vector<Entry> entries;
};

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

// φ = 1 + 2 Σ_k ρ_k over the positive head of the residual autocorrelation (lags in samples,
// within one channel and segment): the variance inflation of a mean of correlated residuals.
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

// Runs body(i) for i in [0, n) on up to two threads (the candidates are independent).
void parallelFor(int n, const std::function<void(int)>& body) {
  const int workers = std::max(1u, std::min(2u, std::thread::hardware_concurrency()));
  std::atomic<int> next{0};
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w)
    pool.emplace_back([&] { for (int i; (i = next++) < n;) body(i); });
  for (int i; (i = next++) < n;) body(i);
  for (std::thread& t : pool) t.join();
}

// Residuals of one model on the fit and held-out entries, unweighted.
struct Evaluation {
  Eigen::VectorXd fit, held;
};

// The linearised problem: residual(p) ≈ r0 + Σ_c D_c p_c with D_c the finite-difference column
// of candidate c at the nominal model (exact for the effects linear in their parameter).
struct Linearisation {
  Evaluation r0;
  std::vector<Effect> candidates;
  std::vector<Evaluation> columns;
};

struct Fit {
  std::vector<Effect> effects;
  Evaluation r;
  Eigen::MatrixXd JtJ;  // weighted, fit entries
};

std::vector<Effect> candidateEffects(const DiagnoseOptions& o, const MeasuredData& d) {
  std::vector<Effect> out;
  for (int k = 0; k < kNumEffectKinds; ++k) {
    const EffectKind kind = static_cast<EffectKind>(k);
    const EffectInfo& info = effectInfo(kind);
    if (!o.kinds.empty() && std::find(o.kinds.begin(), o.kinds.end(), kind) == o.kinds.end()) continue;
    if (info.needs_torque && !d.has_torque) continue;
    const double neutral = info.factor ? 1.0 : 0.0;
    if (!info.per_joint) {
      out.push_back({kind, kNoJoint, neutral});
      continue;
    }
    for (int j = 0; j < 4; ++j) out.push_back({kind, j, neutral});
    if (kind == EffectKind::EncoderOffset) out.push_back({kind, kAlphaJoint, neutral});
  }
  return out;
}

bool sameCandidate(const Effect& a, const Effect& b) { return a.kind == b.kind && a.joint == b.joint; }

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

struct Context {
  const Problem& fit;
  const Problem& held;
  Evaluation evaluate(const std::vector<Effect>& effects) const {
    return evaluate(withEffects(fit.nominal, effects));
  }
  Evaluation evaluate(const RobotParams& robot) const {
    const std::vector<char> all(fit.prepared.data.size(), 1);
    const ResidualMatrix r = residuals(fit.prepared, robot, fit.model_options, all);
    return {entryValues(fit.entries, r), entryValues(held.entries, r)};
  }
};

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

// Chord (frozen-Jacobian Gauss–Newton) iterations from the linearised solution: one model
// evaluation per iteration; exact after one for effects linear in their parameter.
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

// RMS per channel over the reliable entries (those the fit uses) of `entries_a` ∪ `entries_b`,
// per phase over every sample of `rows`, relative to the measured signal's RMS.
// Gauss–Newton iterations with the Jacobian recomputed at the current point (forward
// differences): removes the bias the frozen Jacobian leaves for effects nonlinear in their
// parameter (payload through (1.24), encoder offsets, backlash, slope).
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

ChannelReport channelReport(const PreparedData& p, const std::vector<Entry>& entries_a,
                            const std::vector<Entry>& entries_b, const ResidualMatrix& r,
                            const std::vector<char>& rows, const RobotParams& robot,
                            const ModelOptions& mo) {
  ChannelReport rep;
  const MeasuredData& d = p.data;
  std::array<double, kNumChannels> s{}, n{}, signal{};
  for (const auto* entries : {&entries_a, &entries_b})
    for (const Entry& e : *entries) {
      const double x = r(e.row, e.channel);
      if (!std::isfinite(x)) continue;
      s[e.channel] += x * x;
      n[e.channel] += 1.0;
      const int c = e.channel;
      if (c >= kGammaKneeLeft && c <= kGammaKneeRight) {
        for (int j = 0; j < 4; ++j)
          if (kGammaKneeLeft + physicalJointOfMotor(j, d.stance[e.row]) == c)
            signal[c] += d.gamma[e.row](j) * d.gamma[e.row](j);
      } else if (c >= kR1x && c <= kR2z) {
        signal[c] += d.reactions[e.row](c - kR1x) * d.reactions[e.row](c - kR1x);
      }
    }
  for (int c = 0; c < kNumChannels; ++c) {
    rep.rms[c] = n[c] > 0 ? std::sqrt(s[c] / n[c]) : kNaN;
    rep.relative_rms[c] = signal[c] > 0.0 ? std::sqrt(s[c] / signal[c]) : kNaN;
    double ph[2] = {0, 0}, np[2] = {0, 0};
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (!rows[i] || !std::isfinite(r(i, c))) continue;
      const int k = d.phase[i] == Phase::SingleSupport ? 0 : 1;
      ph[k] += r(i, c) * r(i, c);
      np[k] += 1.0;
    }
    rep.rms_ss[c] = np[0] > 0 ? std::sqrt(ph[0] / np[0]) : kNaN;
    rep.rms_ds[c] = np[1] > 0 ? std::sqrt(ph[1] / np[1]) : kNaN;
  }
  rep.simulation_error = simulationError(p, robot, mo, rows);
  return rep;
}

double pct(double before, double after) {
  return before > 0.0 && std::isfinite(before) && std::isfinite(after)
             ? 100.0 * (1.0 - after / before)
             : kNaN;
}

}  // namespace

namespace {

ResidualMatrix fitMatrix(std::size_t rows, const std::vector<Entry>& entries,
                         const Eigen::VectorXd& values) {
  ResidualMatrix m = ResidualMatrix::Constant(rows, kNumChannels, kNaN);
  for (std::size_t e = 0; e < entries.size(); ++e) m(entries[e].row, entries[e].channel) = values(e);
  return m;
}

struct Scored {
  std::vector<int> which;  // candidate indices of the model
  CandidateResult result;
  Fit fit;
  double phi = 1.0, s2 = 1.0;
};

// Statistics of a fitted model against the base (the accepted effects) of its round.
// The inflation φ of each channel, weighted by that channel's share of the RSS reduction: the
// autocorrelation that matters is that of the channels carrying the effect.
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

Scored score(const Context& ctx, Fit f, const std::array<double, kNumChannels>& sigma,
             double rss_base, double n, const Eigen::VectorXd& base) {
  Scored s;
  const Eigen::VectorXd r = weightedVector(ctx.fit.entries, f.r.fit, sigma);
  const double k = static_cast<double>(f.effects.size());
  s.phi = signalInflation(ctx.fit.entries, base, r);
  s.s2 = r.squaredNorm() / std::max(1.0, n - k);
  CandidateResult& c = s.result;
  c.all = f.effects;
  c.effect = f.effects.back();
  c.rss = r.squaredNorm();
  c.bic = n / s.phi * std::log(c.rss / n) + k * std::log(n / s.phi);
  const Eigen::MatrixXd cov = f.JtJ.ldlt().solve(Eigen::MatrixXd::Identity(f.JtJ.rows(), f.JtJ.cols()));
  c.stderr_ = std::sqrt(std::max(0.0, s.phi * s.s2 * cov(cov.rows() - 1, cov.cols() - 1)));
  c.p_value = chi2Survival((rss_base - c.rss) / (s.phi * s.s2));
  const Eigen::VectorXd h = weightedVector(ctx.held.entries, f.r.held, sigma);
  c.holdout_rms = std::sqrt(h.squaredNorm() / std::max<Eigen::Index>(1, h.size()));
  s.fit = std::move(f);
  return s;
}

std::vector<char> holdoutRows(const MeasuredData& data, int holdout, int shift, bool held) {
  std::vector<char> rows(data.size(), 0);
  int ordinal = shift - 1;
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (i == 0 || data.step[i] != data.step[i - 1]) ++ordinal;
    rows[i] = (ordinal % holdout == holdout - 1) == held;
  }
  return rows;
}

// Largest relative reduction of a channel's held-out RMS from `before` to `after` [%].
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

// The channels carrying 90 % of the noise-normalised change from `before` to `after`
// (largest first), and the reduction of their noise-normalised RMS [%].
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

struct InertialStage {
  InertialResult result;
  RobotParams robot;
  Eigen::MatrixXd Y;  // weighted regressor, fit entries
  std::array<double, kNumChannels> sigma{};
  Evaluation r;       // residuals of the fitted model
};

// The last-resort `inertial` candidate on top of the accepted model `base` (robot `rb`):
// regressor columns by finite differences (exact: the residuals are affine in the
// parameters), physically consistent weighted LS, reweighted once with the noise levels the
// fit leaves, then the tests of the named candidates with r = rank degrees of freedom.
InertialStage fitInertial(const Context& ctx, const RobotParams& rb, const Fit& base,
                          std::array<double, kNumChannels> sigma, const DiagnoseOptions& o) {
  const std::vector<Entry>& fe = ctx.fit.entries;
  const std::vector<Entry>& he = ctx.held.entries;
  std::vector<Evaluation> cols(kNumInertialParameters);
  parallelFor(kNumInertialParameters, [&](int k) {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(kNumInertialParameters);
    d(k) = inertialScale(k);
    const Evaluation r = ctx.evaluate(withInertialChange(rb, d));
    cols[k] = {(r.fit - base.r.fit) / d(k), (r.held - base.r.held) / d(k)};
  });
  Eigen::MatrixXd Y(fe.size(), kNumInertialParameters);
  ConsistentFit cf;
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      Eigen::VectorXd r = base.r.fit;
      for (int k = 0; k < kNumInertialParameters; ++k) r += cols[k].fit * cf.delta(k);
      sigma = channelSigma(ctx.fit, fitMatrix(ctx.fit.prepared.data.size(), fe, r));
    }
    double column_norm2 = 0.0;  // mean squared norm of the scaled columns
    for (int k = 0; k < kNumInertialParameters; ++k) {
      Y.col(k) = weightedVector(fe, cols[k].fit, sigma);
      column_norm2 += (Y.col(k) * inertialScale(k)).squaredNorm() / kNumInertialParameters;
    }
    // λ: 1e-6 of the data's weight, enough to pin the directions the data do not excite.
    cf = consistentLeastSquares(Y, weightedVector(fe, base.r.fit, sigma), rb, 1e-6 * column_norm2);
  }
  InertialStage st;
  InertialResult& ir = st.result;
  ir.tried = true;
  ir.active = cf.active;
  st.robot = withInertialChange(rb, cf.delta);
  st.Y = Y;
  st.sigma = sigma;
  st.r = ctx.evaluate(st.robot);
  const Evaluation& ev = st.r;
  const Eigen::VectorXd rb_w = weightedVector(fe, base.r.fit, sigma);
  const Eigen::VectorXd r_w = weightedVector(fe, ev.fit, sigma);
  ir.base = baseParameters(Y);
  const double n = static_cast<double>(fe.size());
  const double phi = signalInflation(fe, rb_w, r_w);
  const double s2 = r_w.squaredNorm() / std::max(1.0, n - base.effects.size() - ir.base.rank);
  ir.p_value = chi2Survival((rb_w.squaredNorm() - r_w.squaredNorm()) / (phi * s2), ir.base.rank);
  ir.nominal = inertialParameters(rb);
  ir.fitted = inertialParameters(st.robot);
  ir.base_nominal = ir.base.values(ir.nominal);
  ir.base_fitted = ir.base.values(ir.fitted);
  Eigen::MatrixXd Yb(fe.size(), ir.base.rank);
  for (int i = 0; i < ir.base.rank; ++i) Yb.col(i) = Y.col(ir.base.independent[i]);
  const Eigen::MatrixXd YtY = Yb.transpose() * Yb;
  ir.base_stderr = (phi * s2 * YtY.ldlt().solve(Eigen::MatrixXd::Identity(ir.base.rank, ir.base.rank)))
                       .diagonal().cwiseMax(0.0).cwiseSqrt();
  const Eigen::VectorXd hb = weightedVector(he, base.r.held, sigma);
  const Eigen::VectorXd h = weightedVector(he, ev.held, sigma);
  ir.holdout_rms_before = std::sqrt(hb.squaredNorm() / std::max<Eigen::Index>(1, hb.size()));
  ir.holdout_rms_after = std::sqrt(h.squaredNorm() / std::max<Eigen::Index>(1, h.size()));
  ir.accepted = ir.p_value < o.significance &&
                ir.holdout_rms_after < (1.0 - o.min_inertial_gain / 100.0) * ir.holdout_rms_before &&
                bestChannelGain(he, base.r.held, ev.held) >= o.min_channel_gain;
  return st;
}

// Backward step once `inertial` is in the model: the accepted named effects (candidate
// indices `accepted`, fitted values in `named`) that are no longer significant given the
// others and the inertial parameters (linearised likelihood-ratio test at the final model).
std::vector<int> supersededByInertial(const Context& ctx, const Linearisation& lin,
                                      const std::vector<int>& accepted,
                                      const std::vector<Effect>& named, const InertialStage& st,
                                      double significance) {
  const std::vector<Entry>& fe = ctx.fit.entries;
  const Eigen::VectorXd rf = weightedVector(fe, st.r.fit, st.sigma);
  const double n = static_cast<double>(fe.size());
  const double s2 = rf.squaredNorm() / std::max(1.0, n - accepted.size() - st.result.base.rank);
  const double phi = inflation(fe, rf);
  std::vector<int> dropped;
  for (std::size_t i = 0; i < accepted.size(); ++i) {
    Eigen::MatrixXd A(fe.size(), st.Y.cols() + accepted.size() - 1);
    A.leftCols(st.Y.cols()) = st.Y;
    Eigen::Index col = st.Y.cols();
    for (std::size_t j = 0; j < accepted.size(); ++j)
      if (j != i) A.col(col++) = weightedVector(fe, lin.columns[accepted[j]].fit, st.sigma);
    const Effect& e = named[i];
    const double deviation = effectInfo(e.kind).factor ? e.value - 1.0 : e.value;
    const Eigen::VectorXd b = rf - weightedVector(fe, lin.columns[accepted[i]].fit, st.sigma) * deviation;
    const Eigen::VectorXd x = A.colPivHouseholderQr().solve(-b);
    const double drss = (b + A * x).squaredNorm() - rf.squaredNorm();
    if (chi2Survival(drss / (phi * s2)) >= significance) dropped.push_back(static_cast<int>(i));
  }
  return dropped;
}

constexpr int kRefined = 3;      // candidates refined per round (best linearised RSS)
constexpr int kIterations = 4;   // chord iterations per refinement

}  // namespace

Diagnosis diagnose(const RobotParams& robot, const ModelOptions& mo, const MeasuredData& data,
                   const DiagnoseOptions& o) {
  if (o.holdout < 2) throw std::invalid_argument("--holdout must be >= 2");
  if (o.holdout_shift < 0) throw std::invalid_argument("--holdout-shift must be >= 0");
  const PreparedData prepared(data, o.preprocess);
  const int stages = 2 + o.max_causes + 1;
  const auto progress = [&](const std::string& stage, int done) {
    if (o.on_progress) o.on_progress(stage, done, stages);
  };
  Diagnosis dg;
  dg.fit_rows = holdoutRows(data, o.holdout, o.holdout_shift, false);
  dg.holdout_rows = holdoutRows(data, o.holdout, o.holdout_shift, true);
  const std::vector<char> all(data.size(), 1);
  dg.nominal_residuals = residuals(prepared, robot, mo, all);
  const Problem fit{prepared, robot, mo, dg.fit_rows,
                    fitEntries(prepared, dg.nominal_residuals, dg.fit_rows, o.edge_trim)};
  const Problem held{prepared, robot, mo, dg.holdout_rows,
                     fitEntries(prepared, dg.nominal_residuals, dg.holdout_rows, o.edge_trim)};
  if (fit.entries.empty() || held.entries.empty())
    throw std::invalid_argument("no fit or no held-out samples (too few steps for --holdout)");
  const Context ctx{fit, held};
  const double n = static_cast<double>(fit.entries.size());
  const Evaluation r0{entryValues(fit.entries, dg.nominal_residuals),
                      entryValues(held.entries, dg.nominal_residuals)};
  progress("nominal residuals (" + std::to_string(data.size()) + " samples)", 1);
  const Linearisation lin = linearise(ctx, candidateEffects(o, data), r0);
  progress("screening: " + std::to_string(lin.candidates.size()) + " candidates linearised", 2);
  std::array<double, kNumChannels> sigma = channelSigma(fit, dg.nominal_residuals);
  std::vector<int> accepted, confounded;
  Fit base{{}, r0, {}};
  while (static_cast<int>(accepted.size()) < o.max_causes) {
    sigma = channelSigma(fit, fitMatrix(data.size(), fit.entries, base.r.fit));  // current model
    const Eigen::VectorXd rb = weightedVector(fit.entries, base.r.fit, sigma);
    const double rss_base = rb.squaredNorm();
    // Screening: each remaining candidate with the accepted ones, linearised about the current
    // model (one LS solve for the increments; the accepted effects may be nonlinear).
    std::vector<std::pair<double, int>> order;
    for (int c = 0; c < static_cast<int>(lin.candidates.size()); ++c) {
      if (std::find(accepted.begin(), accepted.end(), c) != accepted.end() ||
          std::find(confounded.begin(), confounded.end(), c) != confounded.end())
        continue;  // in a cause already, or in its class
      std::vector<int> which = accepted;
      which.push_back(c);
      Eigen::MatrixXd J(fit.entries.size(), which.size());
      for (std::size_t i = 0; i < which.size(); ++i)
        J.col(i) = weightedVector(fit.entries, lin.columns[which[i]].fit, sigma);
      const Eigen::VectorXd p = (J.transpose() * J).ldlt().solve(-J.transpose() * rb);
      order.push_back({(rb + J * p).squaredNorm(), c});
    }
    if (order.empty()) break;
    std::sort(order.begin(), order.end());
    // Refinement of the best candidates on the full model.
    const int refined = std::min<int>(kRefined, order.size());
    std::vector<Scored> scored(refined);
    parallelFor(refined, [&](int i) {
      std::vector<int> which = accepted;
      which.push_back(order[i].second);
      Fit f = chordFit(ctx, lin, which, sigma, kIterations);
      const bool linear = std::all_of(f.effects.begin(), f.effects.end(),
                                      [](const Effect& e) { return effectInfo(e.kind).linear; });
      if (!accepted.empty() && !linear) {  // from the accepted values, by Gauss–Newton
        for (std::size_t j = 0; j < accepted.size(); ++j) f.effects[j] = base.effects[j];
        f.r = ctx.evaluate(f.effects);
        f = gaussNewton(ctx, f, sigma, 2);
      }
      scored[i] = score(ctx, f, sigma, rss_base, n, rb);
      scored[i].which = which;
    });
    if (accepted.empty()) {
      for (const Scored& s : scored) dg.candidates.push_back(s.result);
      for (std::size_t i = refined; i < order.size(); ++i) {  // linearised only
        const std::vector<int> which{order[i].second};
        Fit f = chordFit(ctx, lin, which, sigma, 0);
        const Eigen::MatrixXd J = weightedVector(fit.entries, lin.columns[which[0]].fit, sigma);
        const double p = -(J.col(0).dot(weightedVector(fit.entries, r0.fit, sigma))) / J.squaredNorm();
        f.effects[0].value = effectValue(f.effects[0].kind, p);
        f.r = {r0.fit + lin.columns[which[0]].fit * p, r0.held + lin.columns[which[0]].held * p};
        dg.candidates.push_back(score(ctx, f, sigma, rss_base, n, rb).result);
      }
    }
    const auto best = std::min_element(scored.begin(), scored.end(), [](const Scored& a, const Scored& b) {
      return a.result.bic < b.result.bic;
    });
    // The class of the best: candidates statistically indistinguishable from it.
    Cause cause{best->result.effect, 0.0, 1.0, {}};
    const double threshold = chi2Quantile1(o.significance);
    std::vector<int> cls;
    for (const Scored& s : scored)
      if (&s != &*best && s.result.p_value < o.significance &&
          s.result.bic - best->result.bic < threshold) {
        cause.confounded_with.push_back(effectLabel(s.result.effect));
        for (int c = 0; c < static_cast<int>(lin.candidates.size()); ++c)
          if (sameCandidate(lin.candidates[c], s.result.effect)) cls.push_back(c);
      }
    // Reweight with the noise levels the best model leaves (the current model's are
    // conservative where the effect acts) and refit it by Gauss–Newton before testing.
    sigma = channelSigma(fit, fitMatrix(data.size(), fit.entries, best->fit.r.fit));
    const Eigen::VectorXd rb2 = weightedVector(fit.entries, base.r.fit, sigma);
    const Eigen::VectorXd hb2 = weightedVector(held.entries, base.r.held, sigma);
    const Fit refit = std::all_of(best->which.begin(), best->which.end(),
                                  [&](int c) { return effectInfo(lin.candidates[c].kind).linear; })
                          ? chordFit(ctx, lin, best->which, sigma, 1)
                          : gaussNewton(ctx, best->fit, sigma, 3);
    const std::vector<int> best_which = best->which;
    *best = score(ctx, refit, sigma, rb2.squaredNorm(), n, rb2);
    best->which = best_which;
    const CandidateResult& br = best->result;
    if (!(br.p_value < o.significance &&
          br.holdout_rms < std::sqrt(hb2.squaredNorm() / hb2.size()) &&
          bestChannelGain(held.entries, base.r.held, best->fit.r.held) >= o.min_channel_gain)) {
      progress("round " + std::to_string(accepted.size() + 1) + ": no further cause", stages - 1);
      break;
    }
    cause.effect = br.effect;
    cause.stderr_ = br.stderr_;
    cause.p_value = br.p_value;
    confounded.insert(confounded.end(), cls.begin(), cls.end());
    dg.causes.push_back(cause);
    for (const Effect& e : br.all)
      for (int c = 0; c < static_cast<int>(lin.candidates.size()); ++c)
        if (sameCandidate(e, lin.candidates[c]) &&
            std::find(accepted.begin(), accepted.end(), c) == accepted.end())
          accepted.push_back(c);
    // Converge the accepted model, so that the next round credits a candidate only with what
    // it adds, not with a better fit of the effects already accepted.
    base = gaussNewton(ctx, best->fit, sigma, 3);
    progress("round " + std::to_string(dg.causes.size()) + ": " + effectLabel(br.effect),
             2 + static_cast<int>(dg.causes.size()));
  }
  for (std::size_t i = 0; i < dg.causes.size(); ++i) dg.causes[i].effect.value = base.effects[i].value;
  dg.extended_robot = withEffects(robot, base.effects);
  const bool inertial_allowed =
      o.kinds.empty() || std::find(o.kinds.begin(), o.kinds.end(), EffectKind::Inertial) != o.kinds.end();
  if (inertial_allowed) {
    const auto stage = [&](const Fit& b) {
      return fitInertial(ctx, withEffects(robot, b.effects), b,
                         channelSigma(fit, fitMatrix(data.size(), fit.entries, b.r.fit)), o);
    };
    InertialStage st = stage(base);
    const std::vector<int> dropped =
        st.result.accepted ? supersededByInertial(ctx, lin, accepted, base.effects, st, o.significance)
                           : std::vector<int>{};
    if (!dropped.empty()) {  // refit the named effects that remain, then the inertial ones
      std::vector<int> keep;
      std::vector<Cause> causes;
      for (std::size_t i = 0; i < accepted.size(); ++i)
        if (std::find(dropped.begin(), dropped.end(), static_cast<int>(i)) == dropped.end()) {
          keep.push_back(accepted[i]);
          causes.push_back(dg.causes[i]);
        }
      const Fit reduced = keep.empty() ? Fit{{}, r0, {}}
                                       : gaussNewton(ctx, chordFit(ctx, lin, keep, sigma, kIterations), sigma, 3);
      InertialStage st2 = stage(reduced);
      if (st2.result.accepted) {
        for (std::size_t i = 0; i < causes.size(); ++i) causes[i].effect.value = reduced.effects[i].value;
        dg.causes = causes;
        st = std::move(st2);
      }
    }
    dg.inertial = st.result;
    if (st.result.accepted) {
      dg.causes.push_back({{EffectKind::Inertial, kNoJoint, kNaN}, kNaN, st.result.p_value, {}});
      dg.extended_robot = st.robot;
    }
  }
  progress(inertial_allowed ? "inertial stage: " +
                                  std::string(dg.inertial.accepted ? "accepted" : "not accepted")
                            : "inertial stage: not a candidate",
           stages);
  dg.extended_residuals = residuals(prepared, dg.extended_robot, mo, all);
  dg.nominal_all = channelReport(prepared, fit.entries, held.entries, dg.nominal_residuals, all, robot, mo);
  dg.nominal = channelReport(prepared, {}, held.entries, dg.nominal_residuals, dg.holdout_rows, robot, mo);
  dg.extended = channelReport(prepared, {}, held.entries, dg.extended_residuals, dg.holdout_rows,
                              dg.extended_robot, mo);
  const Eigen::VectorXd hn = weightedVector(held.entries, entryValues(held.entries, dg.nominal_residuals), sigma);
  const Eigen::VectorXd he = weightedVector(held.entries, entryValues(held.entries, dg.extended_residuals), sigma);
  dg.nominal.normalised_rms = std::sqrt(hn.squaredNorm() / hn.size());
  dg.extended.normalised_rms = std::sqrt(he.squaredNorm() / he.size());
  for (int c = 0; c < kNumChannels; ++c)
    dg.rms_reduction_pct[c] = pct(dg.nominal.rms[c], dg.extended.rms[c]);
  dg.overall_pct = pct(dg.nominal.normalised_rms, dg.extended.normalised_rms);
  std::tie(dg.effect_channels, dg.effect_channels_pct) = effectChannels(held.entries, hn, he);
  const auto& sn = dg.nominal.simulation_error;
  const auto& se = dg.extended.simulation_error;
  dg.simulation_error_reduction_pct = sn.size() ? pct(sn(5), se(5)) : kNaN;
  dg.smoothing = "local polynomial (Savitzky-Golay) fit of degree " +
                 std::to_string(o.preprocess.order) + " over +-" +
                 std::to_string(static_cast<int>(std::round(o.preprocess.half_window * 1000))) +
                 " ms per phase segment, one-sided at segment ends; alpha row: degree " +
                 std::to_string(o.preprocess.alpha_row_order) + " over +-" +
                 std::to_string(static_cast<int>(std::round(o.preprocess.alpha_row_half_window * 1000))) +
                 " ms";
  return dg;
}

}  // namespace gaitopt
