#pragma once
// What a robot description predicts for measured data, and the residuals measured − predicted
// per sample and channel (step 2 of `gaitopt diagnose`). At the measured kinematics
// (smoothed, corrected for the description's encoder offsets and backlash):
//  - alpha_row (SS): the α-row of (1.32), the moment a point foot would have to supply; 0 if
//    the model were right, available without any torque sensor; with measured centres of
//    pressure the foot moment is measured, and the row has the measured reaction's moment about
//    the stance ankle (at the measured CoP) in place of the model foot's;
//  - gamma_<joint> (SS, DS): measured Γ* − (torque_gain × Γ* + torque_offset), Γ* by (3.57) in
//    SS and (3.62) in DS with R2x measured (or, without reaction columns, the R2x that best fits
//    the measured torques);
//  - R1x, R1z, R2x, R2z: measured − predicted reactions (Newton (1.36), R2 = 0 in SS; in DS
//    R2z by the α-row (3.58) and R1 by (3.59), R2x being measured, so no R2x residual);
//  - ds_foot2_z (DS): height of the rear foot above the ground line z = x tan(slope);
//  - cop1x (SS, with measured centres of pressure): the stance foot's measured CoP travel minus
//    the model's contact-point travel, each about its mean over the stance (the data do not say
//    where the ankle stands): a point foot's contact does not move, a rocker's rolls back by r
//    per radian the tibia turns, −r (α − slope) along the ground. This measures the moment arm
//    of the ground reaction about the point foot, i.e. the foot moment, up to a constant per step.
// Unavailable entries are NaN.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "gaitopt/ident/smoothing_differentiator.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

enum Channel : int {
  kAlphaRow = 0, kGammaKneeLeft, kGammaHipLeft, kGammaHipRight, kGammaKneeRight,
  kR1x, kR1z, kR2x, kR2z, kFoot2z, kCopX, kNumChannels
};
extern const std::array<const char*, kNumChannels> kChannelNames;
extern const std::array<const char*, kNumChannels> kChannelUnits;

// Smoothing parameters of the preprocessing (step 1): degree 8 over ±100 ms, chosen on
// synthetic data as the smallest bias (0.05 N·m on the torques) for q̈ noise about 1 N·m.
// The alpha row (the whole-body moment about the stance foot) weighs α̈ by the whole robot's
// inertia about the foot (~15 kg·m² against ~1 kg·m² for a joint row), so its q̈ noise is
// 4 N·m with the torques' smoother: it uses a smoother of its own, degree 4 over ±150 ms
// (noise 0.5 N·m, noise-free bias 0.1 N·m on synthetic data).
struct PreprocessOptions {
  double half_window = 0.1;  // [s]
  int order = 6;
  double alpha_row_half_window = 0.15;  // [s]
  int alpha_row_order = 4;
};

// The measured data with its segments and smoothed kinematics, computed once.
struct PreparedData {
  PreparedData(const MeasuredData& data, const PreprocessOptions& options = {});
  const MeasuredData& data;
  std::vector<Segment> segments;
  SmoothingDifferentiator differentiator, alpha_row_differentiator;
  Kinematics measured;  // smoothed measured angles and their derivatives
  Kinematics measured_alpha_row;  // the same by the alpha row's smoother
};

using ResidualMatrix = Eigen::Matrix<double, Eigen::Dynamic, kNumChannels, Eigen::RowMajor>;

// Residuals of `robot` (with its sensor model, extras, payload, slope) on the samples whose
// `rows` flag is set (other rows NaN).
ResidualMatrix residuals(const PreparedData& prepared, const RobotParams& robot,
                         const ModelOptions& model_options, const std::vector<char>& rows);

// Open-loop forward simulation of each single-support segment of `rows` from its measured
// initial state, driven by the measured torques (sensor model inverted): RMS over the samples
// of simulated − measured α and joint angles [rad], per physical joint (index 0 = α, 1..4 =
// knee_left..knee_right), and overall. Empty (size 0) without torque columns.
Eigen::VectorXd simulationError(const PreparedData& prepared, const RobotParams& robot,
                                const ModelOptions& model_options, const std::vector<char>& rows);

}  // namespace gaitopt
