#include "gaitopt/opt/random_start.hpp"

#include <algorithm>

namespace gaitopt {

namespace {

// Lowest / highest values a start may take for the parameters with a sign requirement.
constexpr double kMinStepLength = 0.05;    // m, the optimiser's lower bound on d
constexpr double kMinSwingHeight = 0.005;  // m, z2_int > 0
constexpr double kMaxAlphadot = -0.05;     // rad/s, α̇_iSS < 0
constexpr double kMinTDS = 0.02;           // s, T_DS > 0.01 s (the optimiser's lower bound)

// Uniform in [0, 1) from the top 53 bits of one draw: fixed by the standard, unlike
// std::uniform_real_distribution, whose algorithm is implementation-defined.
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

GaitParameters randomStartHalfWidths(const Parameterisation& par) {
  GaitParameters h(kNumGaitParameters);
  // α, δ1, θ3, d, α, δ1, θ3, δ1, θ3, x2r, z2, α̇, δ1*, δ2*, δ1*, δ2*, T_DS
  h << 0.15, 0.15, 0.1, 0.05, 0.15, 0.15, 0.1, 0.15, 0.1, 0.05, 0.02, 0.3, 0.5, 0.5, 0.5, 0.5,
      0.05;
  return extendPerParameter(h, par, {0.15, 0.15}, {0.15, 0.1});
}

RandomStartBox randomStartBox(const GaitParameters& centre, const Parameterisation& par,
                              double scale) {
  const GaitParameters h = scale * randomStartHalfWidths(par);
  RandomStartBox box{centre - h, centre + h};
  box.lower(kStepLength) = std::max(box.lower(kStepLength), kMinStepLength);
  box.lower(kZ2Int) = std::max(box.lower(kZ2Int), kMinSwingHeight);
  box.lower(kTDS) = std::max(box.lower(kTDS), kMinTDS);
  box.upper(kAlphadotISS) = std::min(box.upper(kAlphadotISS), kMaxAlphadot);
  // A centre already beyond a limit gives a degenerate interval at the limit.
  box.lower(kAlphadotISS) = std::min(box.lower(kAlphadotISS), box.upper(kAlphadotISS));
  box.upper = box.upper.cwiseMax(box.lower);
  return box;
}

GaitParameters randomStart(const GaitParameters& centre, std::mt19937_64& rng,
                           const Parameterisation& par, double scale) {
  const RandomStartBox box = randomStartBox(centre, par, scale);
  GaitParameters p(par.size());
  for (int i = 0; i < par.size(); ++i) {
    p(i) = box.lower(i) + unit(rng) * (box.upper(i) - box.lower(i));
  }
  return p;
}

}  // namespace gaitopt
