#pragma once
// The held-out gain of a diagnosis with an interval (ident/diagnose.hpp): every step in turn is
// left out, the model's parameters refitted on the other steps and the left-out step predicted;
// the gain is the reduction of the noise-normalised RMS of those predictions against a base
// model's residuals, and its 95 % interval a bootstrap over the steps (each step's predictions
// are one draw: the residuals within a step are correlated, those of different steps hardly).
// A fixed split holds out a few steps, so on a short recording one partial step can swing the
// gain; this uses every step.
// The refit is linearised about the fitted parameters (Jacobian by forward differences there):
// exact for the effects linear in their parameter, and the left-out step moves the others little.
#include <array>
#include <vector>

#include "gaitopt/ident/diagnosis_fit.hpp"

namespace gaitopt::diagnosis {

class LeaveOneStepOut {
 public:
  // The predictions of the left-out steps by `model` (its effects fitted), weighted by 1/σ.
  LeaveOneStepOut(const Context& ctx, const Fit& model, const std::array<double, kNumChannels>& sigma);
  // The gain of the predictions over the residuals `base` (fit and held-out entries) on
  // `channels`.
  GainInterval gain(const Evaluation& base, const std::vector<int>& channels) const;
  // The channels the model acts on relative to `base` (ident/diagnosis_fit.hpp actingChannels).
  std::vector<int> acting(const Evaluation& base, double share) const;

 private:
  Eigen::VectorXd weighted(const Evaluation& e) const;
  std::vector<Entry> entries_;  // fit then held-out entries
  std::vector<int> step_;       // ordinal of each entry's step
  int steps_ = 0;
  std::array<double, kNumChannels> sigma_;
  Eigen::VectorXd fitted_, predicted_;  // weighted residuals: all steps fitted; each step left out
};

}  // namespace gaitopt::diagnosis
