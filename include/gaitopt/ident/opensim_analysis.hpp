#pragma once
// What a point-foot five-link model makes of a person's walking (an imported OpenSim trial):
// (a) inverse dynamics of the floating model (1.1) with the measured reactions applied at the
// measured centres of pressure, hip and knee torques against OpenSim's reference moments;
// (b) the single-support α-row residual — the moment about the stance "point foot" (the
// ankle) that the ground would have to provide — against the moment the measured reaction
// actually has about that point; (c) the rocker-foot radius r: a rolling arc foot moves its
// contact point by r × (rotation of the stance shank), fitted on one leg's stances and tested
// on the other's, against the roll-over-shape value ≈ 0.3 × leg length.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "gaitopt/ident/opensim_import.hpp"
#include "gaitopt/ident/recorded_tables.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

// One stance of a foot while it is leg 1 (heel strike to the other foot's heel strike).
struct StanceSamples {
  BodySide side = BodySide::Right;
  Eigen::VectorXd shank;   // stance-shank angle α [rad]
  Eigen::VectorXd cop_x;   // centre of pressure, belt removed [m]
  Eigen::VectorXd weight;  // vertical force [N] (weights: the CoP is uncertain at low force)
};

// Radius r of the model cop_x = c_k − r α (one offset c_k per stance, r common) by weighted
// least squares: the CoP of a rolling arc moves forward by r per radian the shank turns
// forward (α decreases). 0 when the stances have no shank rotation.
double fitRockerRadius(const std::vector<StanceSamples>& stances);

// Weighted RMS of the CoP about the model with radius r, offsets refitted per stance
// (r = 0: the point foot, whose contact point cannot move within a stance).
double rockerCopRms(const std::vector<StanceSamples>& stances, double radius);

struct RockerFootReport {
  double radius_right = 0, radius_left = 0, radius_all = 0;  // fitted on those stances [m]
  // Held out: r fitted on one leg, CoP RMS on the other's stances; both directions pooled.
  double holdout_rms_point = 0, holdout_rms_rocker = 0, holdout_gain_pct = 0;
  double leg_length = 0;         // hip height above the ground, maximum over the trial [m]
  double literature_radius = 0;  // 0.3 × leg length (roll-over-shape studies)
  int stances_right = 0, stances_left = 0;
};

struct JointComparison {
  std::string joint;  // "hip_right", "knee_right", "hip_left", "knee_left"
  double rms = 0, reference_rms = 0, correlation = 0;
  int samples = 0;
};

struct OpenSimAnalysis {
  std::vector<JointComparison> joints;  // empty without a reference table
  // Single support, inner samples (edge_margin) [N·m]: the α-row residual (what a point foot
  // would need; the point-foot model predicts 0), the measured CoP moment about the ankle, the
  // residual left when the measured CoP is used, and when a rocker foot's CoP is (radius
  // fitted on the other leg, one placement per stance).
  double alpha_residual_rms = 0, cop_moment_rms = 0, alpha_minus_cop_rms = 0;
  double alpha_minus_rocker_rms = 0;
  double alpha_cop_correlation = 0;
  int single_support_samples = 0;
  // Newton residual of the floating model with the measured reactions [N] (x, z rows).
  double force_residual_rms_x = 0, force_residual_rms_z = 0;
  RockerFootReport rocker;
  std::vector<StanceSamples> stances;  // those the rocker was fitted on
  double edge_margin = 0.1;  // [s] left out at both ends of the record (spline end effects)
};

// Stances (leg-1 periods of at least `min_samples` with a foot in contact) of the trial.
std::vector<StanceSamples> importedStances(const ImportedTrial& trial, int min_samples = 60);

// Joint torques Γ (knee 1, hip 1, hip 2, knee 2) at every sample, from the floating model with
// the measured reactions at the CoPs; each torque balances only the links distal to its joint
// (as OpenSim's joint moments do), so errors of the trunk do not leak into the leg torques.
Eigen::MatrixX4d importedJointTorques(const ImportedTrial& trial, const Model& model);

OpenSimAnalysis analyseImportedTrial(const ImportedTrial& trial, const Model& model,
                                     const OpenSimTable* reference_id);

}  // namespace gaitopt
