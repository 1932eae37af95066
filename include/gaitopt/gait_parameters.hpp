#pragma once
// Miossec's 17 gait parameters (§3.2.1.4 with θ3 and T_DS, digest §3.4), in the order and
// with the YAML names of the project. Radians, metres, seconds; `delta*s_*` are ∂δ/∂α.
#include <Eigen/Core>
#include <array>
#include <string>

namespace gaitopt {

constexpr int kNumGaitParameters = 17;

enum GaitParameter : int {
  kAlphaIDS = 0,   // front tibia angle at DS start
  kDelta1IDS,      // front knee at DS start
  kTheta3IDS,      // absolute trunk angle at DS start
  kStepLength,     // d: distance between the feet in DS
  kAlphaFDS,       // DS end (= SS start)
  kDelta1FDS,
  kTheta3FDS,
  kDelta1Int,      // SS configuration at α_int = (α_iSS + α_fSS)/2
  kTheta3Int,
  kX2rInt,         // swing foot x relative to the hip at α_int
  kZ2Int,          // swing foot height at α_int
  kAlphadotISS,    // initial condition of the zero dynamics (< 0)
  kDelta1sISS,     // ∂δ1/∂α at SS start
  kDelta2sISS,
  kDelta1sFSS,     // ∂δ1/∂α at SS end
  kDelta2sFSS,
  kTDS,            // double-support duration
};

extern const std::array<const char*, kNumGaitParameters> kGaitParameterNames;

template <class S> using GaitVector = Eigen::Matrix<S, kNumGaitParameters, 1>;
using GaitParameters = GaitVector<double>;

}  // namespace gaitopt
