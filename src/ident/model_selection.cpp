// Stepwise model selection of the diagnosis: screening of the candidates linearised about the
// current model, refinement and scoring of the best, acceptance tests.
#include "gaitopt/ident/model_selection.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace gaitopt::diagnosis {

namespace {

constexpr int kRefined = 3;  // candidates refined per round (best linearised RSS)

struct Scored {
  std::vector<int> which;  // candidate indices of the model
  CandidateResult result;
  Fit fit;
  double phi = 1.0, s2 = 1.0;
};

// Statistics of a fitted model against the base (the accepted effects) of its round.
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

// Screening: each remaining candidate (neither `accepted` nor `confounded`) with the accepted
// ones, linearised about the current model (one LS solve for the increments; the accepted
// effects may be nonlinear); (weighted RSS, candidate) by increasing RSS.
std::vector<std::pair<double, int>> screen(const Context& ctx, const Linearisation& lin,
                                           const std::vector<int>& accepted,
                                           const std::vector<int>& confounded,
                                           const std::array<double, kNumChannels>& sigma,
                                           const Eigen::VectorXd& rb) {
  std::vector<std::pair<double, int>> order;
  for (int c = 0; c < static_cast<int>(lin.candidates.size()); ++c) {
    if (std::find(accepted.begin(), accepted.end(), c) != accepted.end() ||
        std::find(confounded.begin(), confounded.end(), c) != confounded.end())
      continue;  // in a cause already, or in its class
    std::vector<int> which = accepted;
    which.push_back(c);
    Eigen::MatrixXd J(ctx.fit.entries.size(), which.size());
    for (std::size_t i = 0; i < which.size(); ++i)
      J.col(i) = weightedVector(ctx.fit.entries, lin.columns[which[i]].fit, sigma);
    const Eigen::VectorXd p = (J.transpose() * J).ldlt().solve(-J.transpose() * rb);
    order.push_back({(rb + J * p).squaredNorm(), c});
  }
  std::sort(order.begin(), order.end());
  return order;
}

// Candidate `c` alone, fitted on its linearisation about the nominal model (first round,
// beyond the refined ones).
Fit linearisedFit(const Context& ctx, const Linearisation& lin, int c,
                  const std::array<double, kNumChannels>& sigma) {
  Fit f = chordFit(ctx, lin, {c}, sigma, 0);
  const Eigen::MatrixXd J = weightedVector(ctx.fit.entries, lin.columns[c].fit, sigma);
  const double p = -(J.col(0).dot(weightedVector(ctx.fit.entries, lin.r0.fit, sigma))) / J.squaredNorm();
  f.effects[0].value = effectValue(f.effects[0].kind, p);
  f.r = {lin.r0.fit + lin.columns[c].fit * p, lin.r0.held + lin.columns[c].held * p};
  return f;
}

bool sameCandidate(const Effect& a, const Effect& b) { return a.kind == b.kind && a.joint == b.joint; }

}  // namespace

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

Selection selectCauses(const Context& ctx, const Linearisation& lin,
                       const std::array<double, kNumChannels>& sigma, const DiagnoseOptions& o,
                       const StageProgress& progress) {
  Selection sel{{}, {{}, lin.r0, {}}, sigma, {}, {}};
  const std::size_t rows = ctx.fit.prepared.data.size();
  const double n = static_cast<double>(ctx.fit.entries.size());
  std::vector<int> confounded;
  while (static_cast<int>(sel.accepted.size()) < o.max_causes) {
    sel.sigma = channelSigma(ctx.fit, fitMatrix(rows, ctx.fit.entries, sel.model.r.fit));  // current model
    const Eigen::VectorXd rb = weightedVector(ctx.fit.entries, sel.model.r.fit, sel.sigma);
    const double rss_base = rb.squaredNorm();
    const std::vector<std::pair<double, int>> order =
        screen(ctx, lin, sel.accepted, confounded, sel.sigma, rb);
    if (order.empty()) break;
    // Refinement of the best candidates on the full model.
    const int refined = std::min<int>(kRefined, order.size());
    std::vector<Scored> scored(refined);
    parallelFor(refined, [&](int i) {
      std::vector<int> which = sel.accepted;
      which.push_back(order[i].second);
      Fit f = chordFit(ctx, lin, which, sel.sigma, kIterations);
      const bool linear = std::all_of(f.effects.begin(), f.effects.end(),
                                      [](const Effect& e) { return effectInfo(e.kind).linear; });
      if (!sel.accepted.empty() && !linear) {  // from the accepted values, by Gauss–Newton
        for (std::size_t j = 0; j < sel.accepted.size(); ++j) f.effects[j] = sel.model.effects[j];
        f.r = ctx.evaluate(f.effects);
        f = gaussNewton(ctx, f, sel.sigma, 2);
      }
      scored[i] = score(ctx, f, sel.sigma, rss_base, n, rb);
      scored[i].which = which;
    });
    if (sel.accepted.empty()) {
      for (const Scored& s : scored) sel.candidates.push_back(s.result);
      for (std::size_t i = refined; i < order.size(); ++i)  // linearised only
        sel.candidates.push_back(
            score(ctx, linearisedFit(ctx, lin, order[i].second, sel.sigma), sel.sigma, rss_base, n,
                  rb)
                .result);
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
    sel.sigma = channelSigma(ctx.fit, fitMatrix(rows, ctx.fit.entries, best->fit.r.fit));
    const Eigen::VectorXd rb2 = weightedVector(ctx.fit.entries, sel.model.r.fit, sel.sigma);
    const Eigen::VectorXd hb2 = weightedVector(ctx.held.entries, sel.model.r.held, sel.sigma);
    const Fit refit = std::all_of(best->which.begin(), best->which.end(),
                                  [&](int c) { return effectInfo(lin.candidates[c].kind).linear; })
                          ? chordFit(ctx, lin, best->which, sel.sigma, 1)
                          : gaussNewton(ctx, best->fit, sel.sigma, 3);
    const std::vector<int> best_which = best->which;
    *best = score(ctx, refit, sel.sigma, rb2.squaredNorm(), n, rb2);
    best->which = best_which;
    const CandidateResult& br = best->result;
    if (!(br.p_value < o.significance &&
          br.holdout_rms < std::sqrt(hb2.squaredNorm() / hb2.size()) &&
          bestChannelGain(ctx.held.entries, sel.model.r.held, best->fit.r.held) >= o.min_channel_gain)) {
      progress("round " + std::to_string(sel.accepted.size() + 1) + ": no further cause", progress.stages() - 1);
      break;
    }
    cause.effect = br.effect;
    cause.stderr_ = br.stderr_;
    cause.p_value = br.p_value;
    confounded.insert(confounded.end(), cls.begin(), cls.end());
    sel.causes.push_back(cause);
    for (const Effect& e : br.all)
      for (int c = 0; c < static_cast<int>(lin.candidates.size()); ++c)
        if (sameCandidate(e, lin.candidates[c]) &&
            std::find(sel.accepted.begin(), sel.accepted.end(), c) == sel.accepted.end())
          sel.accepted.push_back(c);
    // Converge the accepted model, so that the next round credits a candidate only with what
    // it adds, not with a better fit of the effects already accepted.
    sel.model = gaussNewton(ctx, best->fit, sel.sigma, 3);
    progress("round " + std::to_string(sel.causes.size()) + ": " + effectLabel(br.effect),
             2 + static_cast<int>(sel.causes.size()));
  }
  for (std::size_t i = 0; i < sel.causes.size(); ++i) sel.causes[i].effect.value = sel.model.effects[i].value;
  return sel;
}

}  // namespace gaitopt::diagnosis
