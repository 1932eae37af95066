#pragma once
// Helpers shared by the identification tests.
#include "gaitopt/ident/residual_model.hpp"

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

}  // namespace gaitopt::test
