#pragma once
// Random starting points for multi-start optimisation: uniform in a box around a centre (the
// configured initial guess, by default defaultInitialGuess), with half-widths of the order of
// the differences between the thesis' optimal gaits, clipped where a parameter must keep its
// sign. Draws use only std::mt19937_64 (whose sequence the C++ standard fixes) and an explicit
// 53-bit mapping to [0, 1), so the same seed gives the same starts on every platform.
#include <random>

#include "gaitopt/gait/parameters.hpp"

namespace gaitopt {

struct RandomStartBox {
  GaitParameters lower, upper;
};

// Half-widths, in parameter order: α_iDS, α_fDS ±0.15 rad; δ1_iDS, δ1_fDS, δ1_int ±0.15 rad;
// θ3_iDS, θ3_fDS, θ3_int ±0.1 rad; d ±0.05 m; x2r_int ±0.05 m; z2_int ±0.02 m;
// α̇_iSS ±0.3 rad/s; the four slopes ∂δ/∂α ±0.5; T_DS ±0.05 s.
GaitParameters randomStartHalfWidths(const Parameterisation& par = {});

// [centre − scale × half-width, centre + scale × half-width], then clipped so that z2_int ≥ 0.005 m,
// α̇_iSS ≤ −0.05 rad/s and T_DS ≥ 0.02 s (and d ≥ 0.05 m): a start keeps a swing foot above
// the ground, a forward stance-tibia rate and a positive double support.
RandomStartBox randomStartBox(const GaitParameters& centre, const Parameterisation& par = {},
                              double scale = 1.0);

// One point drawn uniformly in randomStartBox(centre, par, scale): one draw of `rng` per
// parameter, in order.
GaitParameters randomStart(const GaitParameters& centre, std::mt19937_64& rng,
                           const Parameterisation& par = {}, double scale = 1.0);

}  // namespace gaitopt
