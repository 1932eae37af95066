#pragma once
// `gaitopt diagnose`: where a robot model's predictions and measured data disagree,
// which candidate effect (ident/effects.hpp) explains it, and how much better the extended model
// predicts steps it was not fitted on.
//
// Fit: every candidate (effect, physical joint) has one parameter, fitted by Gauss–Newton on
// the weighted residuals of the fit steps (central-difference Jacobian; one iteration is exact
// for the effects linear in their parameter). Weights 1/σ_c² per channel, σ_c the RMS residual
// of the current model in that channel (noise estimated from the data, conservative while an
// effect is unexplained). Channels: the single-support alpha_row, torque and reaction residuals
// (samples within edge_trim of a phase boundary left out: the smoothing differentiator is
// one-sided there) and the double-support ds_foot2_z; double-support dynamics are reported but
// not fitted (a 40 ms phase is too short to differentiate quantised angles twice).
// Selection: by increasing BIC, the first refined candidate accepted when an F-type test
// (Δ weighted RSS over the residual
// variance, inflated by the residual autocorrelation: effective sample size n/φ,
// φ = 1 + 2 Σ_k ρ_k) gives p < significance AND the held-out error decreases. Candidates whose
// fit is statistically indistinguishable from the best and
// significant themselves are reported in `confounded_with` (BIC within the test's χ²₁
// threshold of the best: the same number of parameters, so ΔBIC is the likelihood ratio).
// A cause must also reduce the held-out RMS of at least one channel by min_channel_gain %.
// Then stepwise: the remaining candidates are screened linearised about the current model and
// the best refitted jointly with the accepted effects (Gauss–Newton from their converged
// values), up to max_causes.
// Last resort, when no named candidate passes (and fewer than max_causes are accepted): the
// `inertial` candidate, the base inertial parameters (ident/inertial_fit.hpp) fitted on top
// of the accepted effects by physically consistent weighted least squares, accepted by the
// same tests with r = rank degrees of freedom (χ²_r); then a backward step drops the accepted
// named effects it makes insignificant and refits the rest.
// Not over-reaching: a cause must be admissible (ident/admissible_range.hpp; an encoder offset
// also above the data's angle resolution; the inertial fit with no consistency constraint
// binding), its value at the converged model still significant, and it must leave no
// significant structured residual (ident/structured_residual.hpp) on a channel it acts on;
// otherwise it is a partial fit. Nor is a cause whose held-out gain, every step left out in
// turn, has a 95 % interval including zero (ident/leave_one_step_out.hpp): the data do not
// decide it. `unexplained`: the channels whose held-out residual is still
// structured after the causes, with the partial fits that act on them.
// Gain: effect_channels_pct, on the channels the causes act on (those carrying 90 % of the
// noise-normalised change in the held-out predictions); overall_pct over every channel.
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "gaitopt/ident/effects.hpp"
#include "gaitopt/ident/inertial_fit.hpp"
#include "gaitopt/ident/residual_model.hpp"

namespace gaitopt {

struct DiagnoseOptions {
  int holdout = 3;                 // every K-th step held out (K >= 2)
  // Steps whose ordinal + holdout_shift is ≡ K − 1 (mod K) are held out: with K = 2 and
  // shifts 0 and 1 the two runs swap the fit and held-out steps (e.g. one leg's stances each).
  int holdout_shift = 0;
  std::vector<EffectKind> kinds;   // candidate effects; empty: all
  double significance = 0.01;
  // Practical significance: a cause must also cut the held-out RMS of some channel by this
  // much [%] (a statistically significant but tiny effect may be a bias of the smoothing).
  double min_channel_gain = 10.0;
  // The last-resort `inertial` stage (7+ base parameters) must also cut the held-out weighted
  // RMS over all channels by this much [%]: a few-% gain is what such a flexible fit gets from
  // the smoothing bias of a large named effect (a 4 cm foot offset gave 1.7 %).
  double min_inertial_gain = 5.0;
  // A channel's held-out residual is structured (not explained) when its cross-step prediction
  // (ident/structured_residual.hpp) is significant and removes at least this much of its RMS [%].
  double min_unexplained_gain = 30.0;
  // A cause must leave less structure than this on the channels it acts on [%]: a combination of
  // library effects can mimic most of an effect outside the library.
  double min_overreach_gain = 20.0;
  // ... and an unexplained structure must exceed this share of the channel's measured torque or
  // reaction RMS (encoder quantisation alone leaves a few-% structure in the reactions).
  double unexplained_signal_share = 0.05;
  int max_causes = 3;
  double edge_trim = 0.03;         // [s]
  PreprocessOptions preprocess;
  // Called after each stage with its description and `done` of `total` stages (the nominal
  // residuals, the screening, one per selection round, the inertial stage); a round that
  // finds no further cause jumps `done` to the last stage. Empty: no progress.
  std::function<void(const std::string& stage, int done, int total)> on_progress;
};

struct ChannelReport {
  std::array<double, kNumChannels> rms{}, rms_ss{}, rms_ds{}, relative_rms{};  // NaN: no data
  Eigen::VectorXd simulation_error;  // α, knee_left..knee_right, overall [rad]; empty: no torque
  double normalised_rms = 0.0;       // RMS of the weighted fit residuals (noise units)
};

struct CandidateResult {
  Effect effect;        // fitted value
  double stderr_ = 0.0;
  double rss = 0.0;     // weighted, fit steps
  double bic = 0.0;
  double holdout_rms = 0.0;  // normalised, held-out steps
  double p_value = 1.0;
  std::vector<Effect> all;   // every effect of the model (accepted ones refitted)
};

struct InertialResult {
  bool tried = false, accepted = false;
  BaseParameters base;
  Eigen::VectorXd nominal, fitted;  // (m, h, J) of tibia, femur, trunk
  Eigen::VectorXd base_nominal, base_fitted, base_stderr;
  std::vector<std::string> active;  // consistency constraints binding the fit
  double p_value = 1.0;
  double holdout_rms_before = 0.0, holdout_rms_after = 0.0;  // normalised, held-out steps
};

// A held-out gain from leaving out every step in turn (ident/leave_one_step_out.hpp), with its
// 95 % interval over the steps [%]; NaN when not computed.
struct GainInterval {
  double pct = std::numeric_limits<double>::quiet_NaN();
  double low_pct = std::numeric_limits<double>::quiet_NaN();
  double high_pct = std::numeric_limits<double>::quiet_NaN();
  int steps = 0;
  bool decided() const { return low_pct > 0.0; }  // the interval excludes zero
};

struct Cause {
  Effect effect;
  double stderr_ = 0.0, p_value = 1.0;
  std::vector<std::string> confounded_with;
  GainInterval step_gain;  // over the model without this cause, on the channels it acts on
};

// What an unexplained residual follows best (ident/structured_residual.hpp).
enum class Signature { JointAngle, Velocity, Acceleration, Torque, TorqueShift, None };
const char* signatureName(Signature s);  // "joint angle", …, "none"

// A library candidate that reduces a residual but is not its cause: its fitted value is outside
// its physical range (ident/admissible_range.hpp), or it leaves a significant structured residual
// on a channel it acts on.
struct PartialFit {
  Effect effect;
  double p_value = 1.0;
  std::string reason;
  std::vector<int> channels;  // the channels it acts on
};

// A channel whose held-out residual, after the causes, is still significant and structured.
struct Unexplained {
  int channel = 0;
  int joint = kNoJoint;  // the physical joint of a joint-torque channel
  double heldout_rms = 0.0, noise_rms = 0.0, p_value = 1.0;
  Signature signature = Signature::None;
  std::vector<PartialFit> partial_fits;  // candidates acting on this channel that are not causes
};

// With measured centres of pressure: the rocker radius they give alone (ident/cop_radius.hpp)
// and the one the diagnosis fitted (the `rocker_foot` cause, or its first-round candidate when it
// is not a cause), both total [m], and their difference relative to the CoP's [%].
struct CopComparison {
  bool used = false;
  double radius_cop = std::numeric_limits<double>::quiet_NaN();
  double radius_cop_stderr = std::numeric_limits<double>::quiet_NaN();
  double radius_fit = std::numeric_limits<double>::quiet_NaN();
  double radius_fit_stderr = std::numeric_limits<double>::quiet_NaN();
  bool fit_is_cause = false;
  double difference_pct = std::numeric_limits<double>::quiet_NaN();
};

struct Diagnosis {
  std::vector<char> holdout_rows, fit_rows;
  ChannelReport nominal_all, nominal, extended;  // nominal_all: every step; others: held out
  std::vector<CandidateResult> candidates;       // first round, every candidate
  std::vector<Cause> causes;
  std::vector<Unexplained> unexplained;  // by channel
  std::vector<PartialFit> partial_fits;  // every candidate rejected as a cause
  RobotParams extended_robot;
  ResidualMatrix nominal_residuals, extended_residuals;  // every sample
  std::array<double, kNumChannels> rms_reduction_pct{};
  double overall_pct = 0.0, simulation_error_reduction_pct = 0.0;
  std::string smoothing;  // description of the differentiator
  InertialResult inertial;
  // The gain where the causes act: the channels carrying 90 % of the (noise-normalised) change
  // the extended model makes to the held-out predictions, and the reduction of their
  // noise-normalised held-out RMS [%].
  std::vector<int> effect_channels;
  double effect_channels_pct = 0.0;
  // The named causes' model against the nominal one on the channels it acts on, every step left
  // out in turn (NaN without a named cause or with the inertial cause).
  GainInterval step_gain;
  CopComparison cop;
};

// Throws std::invalid_argument for holdout < 2 or when fewer than two fit steps remain.
Diagnosis diagnose(const RobotParams& robot, const ModelOptions& model_options,
                   const MeasuredData& data, const DiagnoseOptions& options = {});

}  // namespace gaitopt
