#pragma once
// The rocker-foot radius the measured centres of pressure give on their own (the cop1x channel of
// ident/residual_model.hpp): per single-support stance, the CoP travel about its mean regressed
// on the contact-point travel of a unit rocker, −(α − slope) cos(slope) about its mean; one
// radius for all stances, least squares. Its standard error accounts for the autocorrelation of
// the residuals (effective sample size n/φ, ident/diagnosis_fit.hpp inflation).
#include <vector>

#include "gaitopt/ident/residual_model.hpp"

namespace gaitopt {

struct CopRadius {
  double radius = 0.0, stderr_ = 0.0;  // [m], total (the robot file's radius included)
  int samples = 0;
};

// Needs data with centres of pressure (std::invalid_argument otherwise); `rows`: the samples used.
CopRadius copRadius(const PreparedData& prepared, const RobotParams& robot,
                    const ModelOptions& model_options, const std::vector<char>& rows);

}  // namespace gaitopt
