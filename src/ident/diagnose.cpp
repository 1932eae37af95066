// The model diagnosis: the fit and held-out problems, the selection and the inertial stage
// (ident/model_selection.hpp, ident/inertial_stage.hpp), then the reports of the nominal and
// extended models.
#include "gaitopt/ident/diagnose.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "gaitopt/ident/cop_radius.hpp"
#include "gaitopt/ident/inertial_stage.hpp"
#include "gaitopt/ident/leave_one_step_out.hpp"
#include "gaitopt/ident/model_selection.hpp"
#include "gaitopt/ident/structured_residual.hpp"

namespace gaitopt {

using namespace diagnosis;

namespace {

// RMS per channel over the reliable entries (those the fit uses) of `entries_a` ∪ `entries_b`,
// per phase over every sample of `rows`, relative to the measured signal's RMS.
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

std::vector<char> holdoutRows(const MeasuredData& data, int holdout, int shift, bool held) {
  std::vector<char> rows(data.size(), 0);
  int ordinal = shift - 1;
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (i == 0 || data.step[i] != data.step[i - 1]) ++ordinal;
    rows[i] = (ordinal % holdout == holdout - 1) == held;
  }
  return rows;
}

// The `inertial` cause, like a named one, must be admissible — its physically consistent fit
// inside the consistent set, no constraint binding — and leave no structured residual on the
// channels it acts on; otherwise it is a partial fit and the named causes of `sel` are the model.
void dropOverreachingInertial(const Context& ctx, const Selection& sel, const DiagnoseOptions& o,
                              Diagnosis& dg) {
  if (!dg.inertial.accepted) return;
  const Evaluation ext = ctx.evaluate(dg.extended_robot);
  const std::vector<int> channels =
      actingChannels(ctx.held.entries, sel.model.r.held, ext.held, o.min_channel_gain / 100.0);
  std::vector<int> left;
  for (const ChannelTest& t : testChannels(ctx, ext, o, overreachThreshold(o)))
    if (t.structured && std::find(channels.begin(), channels.end(), t.channel) != channels.end())
      left.push_back(t.channel);
  std::string binding;
  for (const std::string& a : dg.inertial.active) binding += (binding.empty() ? "" : ", ") + a;
  if (left.empty() && binding.empty()) return;
  dg.partial_fits.push_back({dg.causes.back().effect, dg.inertial.p_value,
                             binding.empty()
                                 ? "the inertial parameters reduce the residual but leave a "
                                   "significant structured residual on " + channelList(left)
                                 : "best inertial fit: on the boundary of physical consistency (" +
                                       binding + " binding)",
                             channels});
  dg.inertial.accepted = false;
  dg.causes = sel.causes;
  dg.extended_robot = withEffects(ctx.fit.nominal, sel.model.effects);
}

// The channels whose held-out residual `r` is still structured, with the partial fits that act
// on them.
std::vector<Unexplained> unexplained(const Context& ctx, const Evaluation& r, const DiagnoseOptions& o,
                                     const std::vector<PartialFit>& partial) {
  std::vector<Unexplained> out;
  for (const ChannelTest& t : testChannels(ctx, r, o, unexplainedThreshold(o))) {
    if (!t.structured) continue;
    Unexplained u;
    u.channel = t.channel;
    const bool joint = t.channel >= kGammaKneeLeft && t.channel <= kGammaKneeRight;
    u.joint = joint ? t.channel - kGammaKneeLeft : kNoJoint;
    u.heldout_rms = t.heldout_rms;
    u.noise_rms = t.noise_rms;
    u.p_value = t.p_value;
    u.signature = t.signature;
    for (const PartialFit& f : partial)
      if (std::find(f.channels.begin(), f.channels.end(), t.channel) != f.channels.end())
        u.partial_fits.push_back(f);
    out.push_back(u);
  }
  return out;
}

// The rocker radius of the measured centres of pressure against the diagnosis' (CopComparison).
CopComparison compareCop(const PreparedData& p, const RobotParams& robot, const ModelOptions& mo,
                         const Diagnosis& dg) {
  CopComparison c;
  if (!p.data.has_cop) return c;
  c.used = true;
  const CopRadius cop = copRadius(p, robot, mo, std::vector<char>(p.data.size(), 1));
  c.radius_cop = cop.radius;
  c.radius_cop_stderr = cop.stderr_;
  const auto rocker = [](const Effect& e) { return e.kind == EffectKind::RockerFoot; };
  for (const Cause& k : dg.causes)
    if (rocker(k.effect)) {
      c.radius_fit = robot.foot_radius + k.effect.value;
      c.radius_fit_stderr = k.stderr_;
      c.fit_is_cause = true;
    }
  for (const CandidateResult& k : dg.candidates)
    if (!c.fit_is_cause && rocker(k.effect)) {
      c.radius_fit = robot.foot_radius + k.effect.value;
      c.radius_fit_stderr = k.stderr_;
    }
  c.difference_pct = 100.0 * (c.radius_fit - c.radius_cop) / c.radius_cop;
  return c;
}

}  // namespace

const char* signatureName(Signature s) {
  static const std::array<const char*, 6> names = {"joint angle", "velocity", "acceleration",
                                                   "torque", "torque time shift", "none"};
  return names[static_cast<int>(s)];
}

Diagnosis diagnose(const RobotParams& robot, const ModelOptions& mo, const MeasuredData& data,
                   const DiagnoseOptions& o) {
  if (o.holdout < 2) throw std::invalid_argument("--holdout must be >= 2");
  if (o.holdout_shift < 0) throw std::invalid_argument("--holdout-shift must be >= 0");
  const PreparedData prepared(data, o.preprocess);
  const StageProgress progress{o};
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
  const Evaluation r0{entryValues(fit.entries, dg.nominal_residuals),
                      entryValues(held.entries, dg.nominal_residuals)};
  progress("nominal residuals (" + std::to_string(data.size()) + " samples)", 1);
  const Linearisation lin = linearise(ctx, candidateEffects(o, data), r0);
  progress("screening: " + std::to_string(lin.candidates.size()) + " candidates linearised", 2);
  Selection sel = selectCauses(ctx, lin, channelSigma(fit, dg.nominal_residuals), o, progress);
  dropOverreaching(ctx, lin, sel, o);
  dropUndecided(ctx, lin, sel, o);
  dg.candidates = sel.candidates;
  dg.causes = sel.causes;
  dg.partial_fits = sel.rejected;
  dg.extended_robot = withEffects(robot, sel.model.effects);
  const bool inertial_allowed =
      o.kinds.empty() || std::find(o.kinds.begin(), o.kinds.end(), EffectKind::Inertial) != o.kinds.end();
  if (inertial_allowed) {
    addInertialStage(ctx, lin, sel, o, dg);
    dropOverreachingInertial(ctx, sel, o, dg);
  }
  if (!sel.causes.empty() && !dg.inertial.accepted) {
    const LeaveOneStepOut loso(ctx, sel.model, sel.sigma);
    dg.step_gain = loso.gain(lin.r0, loso.acting(lin.r0, o.min_channel_gain / 100.0));
  }
  progress(inertial_allowed ? "inertial stage: " +
                                  std::string(dg.inertial.accepted ? "accepted" : "not accepted")
                            : "inertial stage: not a candidate",
           progress.stages());
  dg.extended_residuals = residuals(prepared, dg.extended_robot, mo, all);
  dg.unexplained = unexplained(ctx, {entryValues(fit.entries, dg.extended_residuals),
                                     entryValues(held.entries, dg.extended_residuals)},
                               o, dg.partial_fits);
  dg.nominal_all = channelReport(prepared, fit.entries, held.entries, dg.nominal_residuals, all, robot, mo);
  dg.nominal = channelReport(prepared, {}, held.entries, dg.nominal_residuals, dg.holdout_rows, robot, mo);
  dg.extended = channelReport(prepared, {}, held.entries, dg.extended_residuals, dg.holdout_rows,
                              dg.extended_robot, mo);
  const Eigen::VectorXd hn = weightedVector(held.entries, entryValues(held.entries, dg.nominal_residuals), sel.sigma);
  const Eigen::VectorXd he = weightedVector(held.entries, entryValues(held.entries, dg.extended_residuals), sel.sigma);
  dg.nominal.normalised_rms = std::sqrt(hn.squaredNorm() / hn.size());
  dg.extended.normalised_rms = std::sqrt(he.squaredNorm() / he.size());
  for (int c = 0; c < kNumChannels; ++c)
    dg.rms_reduction_pct[c] = pct(dg.nominal.rms[c], dg.extended.rms[c]);
  dg.overall_pct = pct(dg.nominal.normalised_rms, dg.extended.normalised_rms);
  std::tie(dg.effect_channels, dg.effect_channels_pct) = effectChannels(held.entries, hn, he);
  const auto& sn = dg.nominal.simulation_error;
  const auto& se = dg.extended.simulation_error;
  dg.simulation_error_reduction_pct = sn.size() ? pct(sn(5), se(5)) : kNaN;
  dg.cop = compareCop(prepared, robot, mo, dg);
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
