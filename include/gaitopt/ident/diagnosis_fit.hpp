#pragma once
// The fit engine of the model diagnosis (ident/diagnose.hpp): the residual entries a fit uses,
// the noise weights per channel, the candidates linearised by finite differences at the nominal
// model, their chord and Gauss–Newton fits, and the χ² statistics of the tests (variance
// inflated by the residual autocorrelation).
#include <Eigen/Core>
#include <array>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "gaitopt/ident/diagnose.hpp"

namespace gaitopt::diagnosis {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kIterations = 4;  // chord iterations per refinement

// P(χ²_k > x) for an integer k ≥ 1, by the closed forms of the regularised upper incomplete
// gamma function at integer and half-integer order (term t_i = (x/2)^i / Γ(i + 1 or i + 3/2)).
double chi2Survival(double x, int k = 1);

double chi2Quantile1(double tail);  // x with P(χ²₁ > x) = tail, by bisection

// An effect's value from its parameter: 1 + deviation for a factor, else the deviation.
double effectValue(EffectKind kind, double deviation);

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

// The entries of `rows` a fit uses: SS dynamics and DS closure channels with finite residuals,
// SS samples within edge_trim of a phase boundary left out.
std::vector<Entry> fitEntries(const PreparedData& p, const ResidualMatrix& r,
                              const std::vector<char>& rows, double edge_trim);

// φ = 1 + 2 Σ_k ρ_k over the positive head of the residual autocorrelation (lags in samples,
// within one channel and segment): the variance inflation of a mean of correlated residuals.
double inflation(const std::vector<Entry>& entries, const Eigen::VectorXd& r);

// Runs body(i) for i in [0, n) on up to two threads (the candidates are independent).
void parallelFor(int n, const std::function<void(int)>& body);

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

// RMS residual per channel over the problem's entries (1 where a channel has none): the noise
// level σ_c of the weights 1/σ_c².
std::array<double, kNumChannels> channelSigma(const Problem& pb, const ResidualMatrix& r);

// raw residuals of `entries` divided by their channel's σ.
Eigen::VectorXd weightedVector(const std::vector<Entry>& entries, const Eigen::VectorXd& raw,
                               const std::array<double, kNumChannels>& sigma);

// The residuals of `r` at `entries` (0 where not finite).
Eigen::VectorXd entryValues(const std::vector<Entry>& entries, const ResidualMatrix& r);

// The fit and held-out problems; evaluates a model's residuals on both.
struct Context {
  const Problem& fit;
  const Problem& held;
  Evaluation evaluate(const std::vector<Effect>& effects) const;
  Evaluation evaluate(const RobotParams& robot) const;
};

Linearisation linearise(const Context& ctx, const std::vector<Effect>& candidates,
                        const Evaluation& r0);

// Chord (frozen-Jacobian Gauss–Newton) iterations from the linearised solution: one model
// evaluation per iteration; exact after one for effects linear in their parameter.
Fit chordFit(const Context& ctx, const Linearisation& lin, const std::vector<int>& which,
             const std::array<double, kNumChannels>& sigma, int iterations);

// Gauss–Newton iterations with the Jacobian recomputed at the current point (forward
// differences): removes the bias the frozen Jacobian leaves for effects nonlinear in their
// parameter (payload through (1.24), encoder offsets, backlash, slope).
Fit gaussNewton(const Context& ctx, Fit f, const std::array<double, kNumChannels>& sigma,
                int iterations);

// A residual matrix of `rows` rows holding `values` at `entries`, NaN elsewhere.
ResidualMatrix fitMatrix(std::size_t rows, const std::vector<Entry>& entries,
                         const Eigen::VectorXd& values);

// The inflation φ of each channel, weighted by that channel's share of the RSS reduction from
// `base` to `r`: the autocorrelation that matters is that of the channels carrying the effect.
double signalInflation(const std::vector<Entry>& entries, const Eigen::VectorXd& base,
                       const Eigen::VectorXd& r);

// Largest relative reduction of a channel's held-out RMS from `before` to `after` [%].
double bestChannelGain(const std::vector<Entry>& entries, const Eigen::VectorXd& before,
                       const Eigen::VectorXd& after);

// The channels carrying 90 % of the noise-normalised change from `before` to `after` (weighted
// residuals of `entries`), and the reduction of their noise-normalised RMS [%].
std::pair<std::vector<int>, double> effectChannels(const std::vector<Entry>& entries,
                                                   const Eigen::VectorXd& before,
                                                   const Eigen::VectorXd& after);

// The channels a model change acts on: those where the residuals `after` differ from `before`
// by at least `share` of before's RMS on that channel (per channel, so that a channel of few
// entries, like the double-support closure, counts as much as one of many).
std::vector<int> actingChannels(const std::vector<Entry>& entries, const Eigen::VectorXd& before,
                                const Eigen::VectorXd& after, double share);

// Progress of the diagnosis (DiagnoseOptions::on_progress) over its stages: the nominal
// residuals, the screening, one per selection round, the inertial stage.
struct StageProgress {
  const DiagnoseOptions& options;
  int stages() const { return 2 + options.max_causes + 1; }
  void operator()(const std::string& stage, int done) const {
    if (options.on_progress) options.on_progress(stage, done, stages());
  }
};

}  // namespace gaitopt::diagnosis
