#pragma once
// What the diagnosis cannot explain (ident/diagnose.hpp): per channel, whether the residual a
// model leaves on the held-out steps still carries structure, i.e. follows the robot's state
// in a way that repeats from step to step, or is noise.
//
// Signatures: the joint's angle, velocity, acceleration, measured torque and torque rate (a
// time shift of the torque, Γ(t + τ) − Γ(t) ≈ τ Γ̇) for a joint-torque channel, polynomials of
// degree 3; for the other channels α's angle, velocity and acceleration (degree 3) and the four
// motor torques and rates (degree 2). A least-squares fit of the residual on all signatures, on
// the gait phase (piecewise-linear in α, per stance leg: whatever repeats from step to step) and
// an intercept (a constant bias is structure too) on the FIT steps predicts the held-out
// residual ŷ; noise cannot be predicted across steps.
// Test: T = rᵀŷ on the held-out steps, under "noise only" of mean 0 and variance
// φ σ² ‖ŷ‖² (σ² the variance of r − ŷ, the noise; φ = 1 + 2 Σ ρ_k the inflation by the
// autocorrelation of r − ŷ, i.e. the effective sample size n/φ); one-sided normal p-value.
// Structured when p < significance / kNumChannels (Bonferroni over the channels) AND the prediction removes at least
// `min_gain` % of the held-out RMS (the smoothing bias alone is significant on thousands of
// samples) AND the structured RMS √(heldout² − noise²) exceeds the data's raw noise of the
// channel and `signal_share` of its measured signal's RMS.
// The signature reported is the one whose fit alone predicts the held-out residual best, or
// `none` when the intercept alone does.
#include <array>
#include <vector>

#include "gaitopt/ident/diagnosis_fit.hpp"

namespace gaitopt::diagnosis {

struct ChannelTest {
  int channel = 0;
  double heldout_rms = 0.0;  // of the residual, held-out steps [channel unit]
  double noise_rms = 0.0;    // of what no signature predicts
  double p_value = 1.0;
  double gain_pct = 0.0;     // 100 (1 − noise_rms / heldout_rms)
  Signature signature = Signature::None;  // of a structured residual only
  bool structured = false;
};

// 1.4826 × the median absolute deviation: the standard deviation of Gaussian noise, robust to
// the few large deviations where a smoother cannot follow the signal (phase ends, friction sign
// changes).
double robustScatter(std::vector<double> deviations);

// Robust scatter of the measured angles about their smoothed values [rad]: the angle noise of
// the data (about 0.37 encoder count for quantisation alone).
double angleScatter(const PreparedData& p);

struct StructureThreshold {
  double min_gain = 0.0;      // [%]
  double signal_share = 0.0;  // of the measured torque or reaction RMS
};
// Reporting `unexplained`: a structure worth naming; a cause's own channels: any structure left.
inline StructureThreshold unexplainedThreshold(const DiagnoseOptions& o) {
  return {o.min_unexplained_gain, o.unexplained_signal_share};
}
inline StructureThreshold overreachThreshold(const DiagnoseOptions& o) { return {o.min_overreach_gain, 0.0}; }

// The residuals `r` of a model on ctx's fit and held-out entries, tested per channel (channels
// with fewer than 30 entries in either set are left out).
std::vector<ChannelTest> testChannels(const Context& ctx, const Evaluation& r,
                                      const DiagnoseOptions& o, const StructureThreshold& th);

}  // namespace gaitopt::diagnosis
