#pragma once
// Stepwise model selection of the diagnosis (ident/diagnose.hpp): per round the remaining
// candidates screened linearised about the current model, the best refined jointly with the
// accepted effects and scored (BIC, F-type test with the autocorrelation-inflated variance,
// held-out error); the lowest BIC accepted when significant, better on the held-out steps and
// of practical gain; candidates indistinguishable from it recorded as confounded.
#include <array>
#include <string>
#include <vector>

#include "gaitopt/ident/diagnosis_fit.hpp"

namespace gaitopt::diagnosis {

struct Selection {
  std::vector<int> accepted;  // candidate indices (Linearisation::candidates) of the model
  Fit model;                  // the accepted model, converged
  std::array<double, kNumChannels> sigma;  // noise levels of the last model tested
  std::vector<CandidateResult> candidates;  // first round, every candidate
  std::vector<Cause> causes;                // with the values of `model`
  std::vector<PartialFit> rejected;         // candidates that are not causes, and why
};

// Every (effect, physical joint) candidate of the options' kinds that the data can show.
std::vector<Effect> candidateEffects(const DiagnoseOptions& o, const MeasuredData& d);

// Up to max_causes rounds from the nominal model (lin.r0), starting from the noise levels
// `sigma` of the nominal residuals.
Selection selectCauses(const Context& ctx, const Linearisation& lin,
                       const std::array<double, kNumChannels>& sigma, const DiagnoseOptions& o,
                       const StageProgress& progress);

// Selection that does not over-reach: causes no longer significant at the final model are
// dropped; a cause that leaves a significant structured residual
// (ident/structured_residual.hpp) on a channel it acts on is not the cause of that residual: it
// moves to `rejected` and the remaining causes are refitted, until every cause passes.
void dropOverreaching(const Context& ctx, const Linearisation& lin, Selection& sel,
                      const DiagnoseOptions& o);

// A cause whose leave-one-step-out gain over the model without it (on the channels it acts on)
// has a 95 % interval including zero is not decided by the data: it moves to `rejected` and the
// rest are refitted, until every cause is decided. Sets each cause's step_gain.
void dropUndecided(const Context& ctx, const Linearisation& lin, Selection& sel,
                   const DiagnoseOptions& o);

// Names of `channels`, comma-separated.
std::string channelList(const std::vector<int>& channels);

}  // namespace gaitopt::diagnosis
