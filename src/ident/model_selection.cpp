// Stepwise model selection of the diagnosis: screening of the candidates linearised about the
// current model, refinement and scoring of the best, acceptance tests.
#include "gaitopt/ident/model_selection.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <cstdio>

#include "gaitopt/ident/admissible_range.hpp"
#include "gaitopt/ident/leave_one_step_out.hpp"
#include "gaitopt/ident/structured_residual.hpp"

namespace gaitopt::diagnosis {

namespace {

constexpr int kRefined = 3;  // candidates refined per round (best linearised RSS)
// More library effects than this acting on one channel are taken for a combination mimicking
// something the library lacks: three effects of one joint (gain, Coulomb, rotor inertia) fitted
// together reproduce most of a moving knee centre's torque, leaving only a residual the size of
// the smoothing bias.
constexpr int kMaxCausesPerChannel = 2;

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

// Screening: each remaining candidate (not `accepted`; a member of a cause's class may still be
// a second cause: Coulomb and viscous friction of one joint both present) with the accepted
// ones, linearised about the current model (one LS solve for the increments; the accepted
// effects may be nonlinear); (weighted RSS, candidate) by increasing RSS.
std::vector<std::pair<double, int>> screen(const Context& ctx, const Linearisation& lin,
                                           const std::vector<int>& accepted,
                                           const std::array<double, kNumChannels>& sigma,
                                           const Eigen::VectorXd& rb) {
  std::vector<std::pair<double, int>> order;
  for (int c = 0; c < static_cast<int>(lin.candidates.size()); ++c) {
    if (std::find(accepted.begin(), accepted.end(), c) != accepted.end()) continue;
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

// An encoder offset or a backlash smaller than the angle resolution of the data (3 × the angle
// scatter: about one count of a quantising encoder) is what the fit of a nonlinear effect on the
// same channels leaves (e.g. a backlash, whose tanh of the noisy torque is biased), not a cause.
std::string unresolved(const Effect& e, const PreparedData& p) {
  const double resolution = 3.0 * angleScatter(p);
  const bool angle = e.kind == EffectKind::EncoderOffset || e.kind == EffectKind::Backlash;
  if (!angle || std::abs(e.value) >= resolution) return "";
  char b[160];
  std::snprintf(b, sizeof b, "%s %.2g rad is below the angle resolution of the data, %.2g rad",
                effectLabel(e).c_str(), e.value, resolution);
  return b;
}

// Reweights with the noise levels the candidate's model leaves (the current model's are
// conservative where the effect acts: sel.sigma), refits it by Gauss–Newton and rescores it
// (`s` updated); true when it is significant, better on the held-out steps and of practical gain.
bool passesTests(const Context& ctx, const Linearisation& lin, Selection& sel, Scored& s, double n,
                 const DiagnoseOptions& o) {
  const std::size_t rows = ctx.fit.prepared.data.size();
  sel.sigma = channelSigma(ctx.fit, fitMatrix(rows, ctx.fit.entries, s.fit.r.fit));
  const Eigen::VectorXd rb = weightedVector(ctx.fit.entries, sel.model.r.fit, sel.sigma);
  const Eigen::VectorXd hb = weightedVector(ctx.held.entries, sel.model.r.held, sel.sigma);
  const Fit refit = std::all_of(s.which.begin(), s.which.end(),
                                [&](int c) { return effectInfo(lin.candidates[c].kind).linear; })
                        ? chordFit(ctx, lin, s.which, sel.sigma, 1)
                        : gaussNewton(ctx, s.fit, sel.sigma, 3);
  const std::vector<int> which = s.which;
  s = score(ctx, refit, sel.sigma, rb.squaredNorm(), n, rb);
  s.which = which;
  return s.result.p_value < o.significance &&
         s.result.holdout_rms < std::sqrt(hb.squaredNorm() / hb.size()) &&
         bestChannelGain(ctx.held.entries, sel.model.r.held, s.fit.r.held) >= o.min_channel_gain;
}

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
  Selection sel{{}, {{}, lin.r0, {}}, sigma, {}, {}, {}};
  const std::size_t rows = ctx.fit.prepared.data.size();
  const double n = static_cast<double>(ctx.fit.entries.size());
  while (static_cast<int>(sel.accepted.size()) < o.max_causes) {
    sel.sigma = channelSigma(ctx.fit, fitMatrix(rows, ctx.fit.entries, sel.model.r.fit));  // current model
    const Eigen::VectorXd rb = weightedVector(ctx.fit.entries, sel.model.r.fit, sel.sigma);
    const double rss_base = rb.squaredNorm();
    const std::vector<std::pair<double, int>> order =
        screen(ctx, lin, sel.accepted, sel.sigma, rb);
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
    std::vector<int> by_bic(refined);
    std::iota(by_bic.begin(), by_bic.end(), 0);
    std::sort(by_bic.begin(), by_bic.end(),
              [&](int a, int b) { return scored[a].result.bic < scored[b].result.bic; });
    const Scored* lowest = &scored[by_bic[0]];
    // The class of the lowest BIC: candidates statistically indistinguishable from it.
    Cause cause{lowest->result.effect, 0.0, 1.0, {}, {}};
    const double threshold = chi2Quantile1(o.significance);
    for (const Scored& s : scored)
      if (&s != lowest && s.result.p_value < o.significance &&
          s.result.bic - lowest->result.bic < threshold)
        cause.confounded_with.push_back(effectLabel(s.result.effect));
    // By increasing BIC, the first refined candidate that passes the tests is the round's cause:
    // an effect seen on a channel of few entries (a slope in the double-support closure) can rank
    // behind a fit of the noise of the many single-support entries.
    const Scored* best = nullptr;
    for (int i : by_bic) {
      if (passesTests(ctx, lin, sel, scored[i], n, o)) {
        best = &scored[i];
        break;
      }
    }
    if (!best) {
      progress("round " + std::to_string(sel.accepted.size() + 1) + ": no further cause", progress.stages() - 1);
      break;
    }
    if (best != lowest) cause.confounded_with.clear();
    const CandidateResult& br = best->result;
    const std::string outside = unresolved(br.effect, ctx.fit.prepared) + firstInadmissible(br.all, ctx.fit.nominal);
    if (!outside.empty()) {  // the data carry something the library does not describe
      sel.rejected.push_back({br.effect, br.p_value, "best library fit: " + outside,
                              actingChannels(ctx.held.entries, sel.model.r.held, best->fit.r.held,
                                             o.min_channel_gain / 100.0)});
      progress("round " + std::to_string(sel.accepted.size() + 1) + ": best fit not admissible",
               progress.stages() - 1);
      break;
    }
    cause.effect = br.effect;
    cause.stderr_ = br.stderr_;
    cause.p_value = br.p_value;
    sel.causes.push_back(cause);
    for (const Effect& e : br.all)
      for (int c = 0; c < static_cast<int>(lin.candidates.size()); ++c)
        if (sameCandidate(e, lin.candidates[c]) &&
            std::find(sel.accepted.begin(), sel.accepted.end(), c) == sel.accepted.end())
          sel.accepted.push_back(c);
    // Converge the accepted model, so that the next round credits a candidate only with what
    // it adds, not with a better fit of the effects already accepted.
    const Fit converged = gaussNewton(ctx, best->fit, sel.sigma, 3);
    // The round's test credits the new effect with what the joint refit gained, including a
    // better fit of a nonlinear accepted effect; at the converged model the new value itself
    // must still differ significantly from neutral (a backlash once brought a rotor-inertia
    // factor of 1.001 ± 0.008 "with p = 0").
    const Effect& added = converged.effects.back();
    const double deviation = effectInfo(added.kind).factor ? added.value - 1.0 : added.value;
    if (br.stderr_ > 0.0 &&
        chi2Survival(deviation * deviation / (br.stderr_ * br.stderr_)) >= o.significance) {
      sel.causes.pop_back();
      sel.accepted.pop_back();
      // Keep what the joint refit gained for the accepted effects.
      Fit kept{{converged.effects.begin(), converged.effects.end() - 1}, {}, {}};
      kept.r = ctx.evaluate(kept.effects);
      const double before = weightedVector(ctx.fit.entries, sel.model.r.fit, sel.sigma).squaredNorm();
      if (weightedVector(ctx.fit.entries, kept.r.fit, sel.sigma).squaredNorm() < before)
        sel.model = gaussNewton(ctx, kept, sel.sigma, 3);
      progress("round " + std::to_string(sel.causes.size() + 1) + ": no further cause", progress.stages() - 1);
      break;
    }
    sel.model = converged;
    for (Cause& c : sel.causes)  // a class member that is a cause itself is no longer "confounded"
      c.confounded_with.erase(std::remove(c.confounded_with.begin(), c.confounded_with.end(),
                                          effectLabel(br.effect)),
                              c.confounded_with.end());
    progress("round " + std::to_string(sel.causes.size()) + ": " + effectLabel(br.effect),
             2 + static_cast<int>(sel.causes.size()));
  }
  for (std::size_t i = 0; i < sel.causes.size(); ++i) sel.causes[i].effect.value = sel.model.effects[i].value;
  return sel;
}

namespace {

// After a refit without some effects, the remaining ones must still differ significantly from
// neutral (χ²₁ of value over its standard error at the refitted model); those that do not are
// dropped and the rest refitted again.
void dropInsignificant(const Context& ctx, const Linearisation& lin, Selection& sel,
                       const DiagnoseOptions& o) {
  for (bool dropped = true; dropped && !sel.causes.empty();) {
    dropped = false;
    const Eigen::MatrixXd cov = sel.model.JtJ.size() ? sel.model.JtJ.ldlt().solve(
                                    Eigen::MatrixXd::Identity(sel.model.JtJ.rows(), sel.model.JtJ.cols()))
                                                      : Eigen::MatrixXd();
    const Eigen::VectorXd r = weightedVector(ctx.fit.entries, sel.model.r.fit, sel.sigma);
    const double s2 = r.squaredNorm() / std::max(1.0, r.size() - static_cast<double>(sel.causes.size()));
    const double phi = inflation(ctx.fit.entries, r);
    for (std::size_t i = 0; i < sel.causes.size() && cov.rows() == static_cast<Eigen::Index>(sel.causes.size()); ++i) {
      const Effect& e = sel.model.effects[i];
      const double deviation = effectInfo(e.kind).factor ? e.value - 1.0 : e.value;
      const double variance = phi * s2 * cov(i, i);
      if (variance > 0.0 && chi2Survival(deviation * deviation / variance) >= o.significance) {
        sel.causes.erase(sel.causes.begin() + i);
        sel.accepted.erase(sel.accepted.begin() + i);
        sel.model = sel.accepted.empty() ? Fit{{}, lin.r0, {}}
                                         : gaussNewton(ctx, chordFit(ctx, lin, sel.accepted, sel.sigma, kIterations),
                                                       sel.sigma, 3);
        for (std::size_t k = 0; k < sel.causes.size(); ++k) sel.causes[k].effect.value = sel.model.effects[k].value;
        dropped = true;
        break;
      }
    }
  }
}

// The causes `keep` (indices into sel.causes) refitted without the others.
void keepOnly(const Context& ctx, const Linearisation& lin, Selection& sel, const std::vector<int>& keep) {
  std::vector<int> accepted;
  std::vector<Cause> causes;
  for (int i : keep) {
    accepted.push_back(sel.accepted[i]);
    causes.push_back(sel.causes[i]);
  }
  sel.model = accepted.empty()
                  ? Fit{{}, lin.r0, {}}
                  : gaussNewton(ctx, chordFit(ctx, lin, accepted, sel.sigma, kIterations), sel.sigma, 3);
  for (std::size_t i = 0; i < causes.size(); ++i) causes[i].effect.value = sel.model.effects[i].value;
  sel.accepted = accepted;
  sel.causes = causes;
}

}  // namespace

std::string channelList(const std::vector<int>& channels) {
  std::string out;
  for (int c : channels) out += (out.empty() ? "" : ", ") + std::string(kChannelNames[c]);
  return out;
}

void dropOverreaching(const Context& ctx, const Linearisation& lin, Selection& sel,
                      const DiagnoseOptions& o) {
  dropInsignificant(ctx, lin, sel, o);
  while (!sel.causes.empty()) {
    std::array<bool, kNumChannels> structured{};
    for (const ChannelTest& t : testChannels(ctx, sel.model.r, o, overreachThreshold(o)))
      structured[t.channel] = t.structured;
    std::vector<std::vector<int>> channels;
    std::array<int, kNumChannels> crowd{};
    for (std::size_t i = 0; i < sel.causes.size(); ++i) {
      std::vector<Effect> others = sel.model.effects;
      others.erase(others.begin() + i);
      channels.push_back(actingChannels(ctx.held.entries, ctx.evaluate(others).held, sel.model.r.held,
                                        o.min_channel_gain / 100.0));
      for (int c : channels.back()) ++crowd[c];
    }
    std::vector<int> keep;
    for (std::size_t i = 0; i < sel.causes.size(); ++i) {
      std::vector<int> left, crowded;
      for (int c : channels[i]) {
        if (structured[c]) left.push_back(c);
        if (crowd[c] > kMaxCausesPerChannel) crowded.push_back(c);
      }
      if (left.empty() && crowded.empty()) {
        keep.push_back(static_cast<int>(i));
        continue;
      }
      const std::string label = effectLabel(sel.causes[i].effect);
      sel.rejected.push_back({sel.causes[i].effect, sel.causes[i].p_value,
                              left.empty() ? label + " is one of more than two library effects fitted together on " +
                                                 channelList(crowded) + ", which then mimic a structured residual"
                                           : label + " reduces the residual but leaves a significant structured "
                                                     "residual on " + channelList(left),
                              channels[i]});
    }
    if (keep.size() == sel.causes.size()) return;
    keepOnly(ctx, lin, sel, keep);
    dropInsignificant(ctx, lin, sel, o);
  }
}

void dropUndecided(const Context& ctx, const Linearisation& lin, Selection& sel,
                   const DiagnoseOptions& o) {
  while (!sel.causes.empty()) {
    const LeaveOneStepOut loso(ctx, sel.model, sel.sigma);
    std::vector<int> keep;
    for (std::size_t i = 0; i < sel.causes.size(); ++i) {
      std::vector<Effect> others = sel.model.effects;
      others.erase(others.begin() + i);
      const Evaluation base = others.empty() ? lin.r0 : ctx.evaluate(others);
      const std::vector<int> channels = loso.acting(base, o.min_channel_gain / 100.0);
      Cause& c = sel.causes[i];
      c.step_gain = loso.gain(base, channels);
      if (c.step_gain.decided()) {
        keep.push_back(static_cast<int>(i));
        continue;
      }
      char b[200];
      std::snprintf(b, sizeof b,
                    "%s: held-out gain %.0f %%, every step left out in turn, 95 %% interval "
                    "[%.0f, %.0f] %% includes zero: the data do not decide it",
                    effectLabel(c.effect).c_str(), c.step_gain.pct, c.step_gain.low_pct,
                    c.step_gain.high_pct);
      sel.rejected.push_back({c.effect, c.p_value, b, channels});
    }
    if (keep.size() == sel.causes.size()) return;
    keepOnly(ctx, lin, sel, keep);
    dropInsignificant(ctx, lin, sel, o);
  }
}

}  // namespace gaitopt::diagnosis
