#pragma once
// Conversion of an OpenSim walking trial (planar IK coordinates, force-plate reactions, optional
// markers) to the thesis' five-link description sampled at the force-plate rate: absolute
// segment angles smoothed by a cubic smoothing spline, treadmill belt removed, gait events and
// phases from the vertical forces, leg 1 / leg 2 relabelled at each heel strike as in the
// thesis (SS on leg 1; in DS leg 1 is the front leg), and the coordinates q = (α, δ1..δ4) of
// (1.13) with the reactions on leg 1 and leg 2.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "gaitopt/ident/recorded_tables.hpp"
#include "gaitopt/model/robot_params.hpp"

namespace gaitopt {

enum class BodySide { Right = 0, Left = 1 };
inline const char* sideName(BodySide s) { return s == BodySide::Right ? "right" : "left"; }
inline BodySide otherSide(BodySide s) { return s == BodySide::Right ? BodySide::Left : BodySide::Right; }

struct OpenSimRecording {
  OpenSimTable ik;   // IK .mot: pelvis_tilt, pelvis_tx, pelvis_ty, hip_flexion_r/l, knee_angle_r/l, lumbar_extension
  OpenSimTable grf;  // GRF .mot: <prefix>vx, vy, px, py per plate
  std::optional<TrcData> trc;  // markers for the trunk line and the belt speed
};

// Geometry of the scaled OpenSim model that the IK coordinates refer to (defaults: the planar
// gait10dof18musc model scaled to subject01, pelvis frame, metres and kilograms).
struct OpenSimSubjectGeometry {
  Eigen::Vector2d hip_in_pelvis{-0.0724, -0.0677};
  // Only used without markers: trunk line = hip → lumped pelvis + torso CoM.
  double pelvis_mass = 11.375, torso_mass = 33.068;
  Eigen::Vector2d pelvis_com{-0.0724, 0.0}, back_in_pelvis{-0.1032, 0.0835},
      torso_com{-0.0324, 0.3455};  // torso CoM in the torso frame, from the back joint
};

struct OpenSimImportOptions {
  std::optional<double> belt_speed;  // [m/s], > 0 when the belt carries the feet towards −X
  double contact_threshold = 20.0;   // [N]: a foot is in contact while its vertical force exceeds it
  double cutoff_hz = 6.0;            // smoothing-spline gain 1/2 frequency (smoothing_spline.hpp)
  // Trunk line from the pelvis-to-shoulder markers when a .trc is given (the data README's
  // advice); false: through the IK model's lumped pelvis + torso CoM even with markers.
  bool trunk_from_markers = true;
  std::string right_plate = "ground_force_", left_plate = "1_ground_force_";  // GRF column prefixes
  std::vector<std::string> pelvis_markers{"R.ASIS", "L.ASIS", "V.Sacral"};
  std::vector<std::string> shoulder_markers{"R.Acromium", "L.Acromium"};
  std::vector<std::string> heel_markers{"R.Heel", "L.Heel"};  // right, left
  OpenSimSubjectGeometry geometry;
};

// A smoothed signal at the output times: value, first and second time derivative.
struct SmoothedTrajectory {
  Eigen::VectorXd v, d, dd;
};

struct GaitEvent {
  double time;  // threshold crossing, interpolated between force samples [s]
  BodySide side;
  bool heel_strike;  // false: toe off
};

struct ImportedLeg {
  SmoothedTrajectory thigh, shank;  // absolute angles, counter-clockwise from the downward vertical
  Eigen::MatrixX2d force;       // ground reaction on the foot (x forward, z up) [N]
  Eigen::MatrixX2d cop;         // centre of pressure, belt removed [m]
  std::vector<bool> contact;
};

struct ImportedTrial {
  Eigen::VectorXd t;              // output times = force-plate times inside the IK record
  ImportedLeg legs[2];            // indexed by BodySide
  SmoothedTrajectory trunk;           // trunk line angle, counter-clockwise from the upward vertical
  SmoothedTrajectory hip_x, hip_z;    // hip joint centre, belt removed [m]
  double ground_z = 0.0;          // mean COP height (the plate surface) [m]
  std::vector<bool> double_support;
  std::vector<BodySide> leg1;     // physical leg that is leg 1 at each sample
  std::vector<int> step;          // increases at each relabelling (heel strike)
  std::vector<GaitEvent> events;
  double belt_speed = 0.0;
  std::string belt_source;        // "given", "heel markers", "IK ankle"
  std::string trunk_source;       // "markers", "IK model CoM"
  Eigen::MatrixXd q, qd, qdd;     // N × 5, (α, δ1, δ2, δ3, δ4) of (1.13) and derivatives
  Eigen::MatrixXd reactions;      // N × 4: R1x, R1z, R2x, R2z (gravity frame, on the robot)
};

// Converts; data that cannot be labelled (no contact, no single support for the belt
// estimate, force-plate times outside the IK record, a missing column) are DataErrors naming
// the file. `robot` gives the thigh (l2) and shank (l1) lengths. The files are read by
// io/opensim_trial_file.hpp.
ImportedTrial importOpenSimTrial(const OpenSimRecording& recording, const RobotParams& robot,
                                 const OpenSimImportOptions& options = {});

// Ankle position of `side` (hip + femur + shank, lengths of `robot`) at sample k, and its
// horizontal velocity.
Eigen::Vector2d importedAnkle(const ImportedTrial& trial, const RobotParams& robot, BodySide side,
                              Eigen::Index k);
double importedAnkleVelocityX(const ImportedTrial& trial, const RobotParams& robot, BodySide side,
                              Eigen::Index k);

}  // namespace gaitopt
