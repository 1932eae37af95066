#pragma once
// Helpers shared by the identification tests.
#include "gaitopt/ident/residual_model.hpp"
#include "gaitopt/ident/synth.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

// Noise-free data: the least-biased smoother for every row (degree 8 over ±100 ms), so that
// what remains is synth's own inconsistency (the default degree-6 smoother, tuned for noisy
// data, leaves a bias of ~0.2 N·m).
inline PreprocessOptions exactSmoothing() {
  PreprocessOptions o;
  o.order = o.alpha_row_order = 8;
  o.half_window = o.alpha_row_half_window = 0.1;
  return o;
}

// The shipped default gait (robot, parameters, options) the hidden-effect tests synthesise from.
inline const GaitFile& defaultStepGait() {
  static const GaitFile g = loadGaitFile(sourcePath("configs/gait/default_step.yaml"));
  return g;
}

// `steps` steps of synth data from the default gait with hidden and unmodelled effects.
inline MeasuredData synthDefaultStep(const std::vector<Effect>& effects,
                                     const std::vector<UnmodelledEffect>& unmodelled,
                                     std::uint64_t seed, int steps, bool noise = true) {
  SynthOptions o;
  o.steps = steps;
  o.seed = seed;
  o.noise = noise;
  o.unmodelled = unmodelled;
  const GaitFile& g = defaultStepGait();
  return synthesize(g.robot, g.parameters, g.options, g.model_options, effects, o);
}

}  // namespace gaitopt::test
