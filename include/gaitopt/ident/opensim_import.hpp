#pragma once
// Conversion of an OpenSim walking trial (planar IK coordinates, force-plate reactions, optional
// markers) to the thesis' five-link description sampled at the force-plate rate: absolute
// segment angles smoothed by a cubic smoothing spline, treadmill belt removed, gait events and
// phases from the vertical forces, leg 1 / leg 2 relabelled at each heel strike as in the
// thesis (SS on leg 1; in DS leg 1 is the front leg), and the coordinates q = (α, δ1..δ4) of
// (1.13) with the reactions on leg 1 and leg 2.
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gaitopt/ident/opensim_conventions.hpp"
#include "gaitopt/ident/recorded_tables.hpp"
#include "gaitopt/model/robot_params.hpp"

namespace gaitopt {

enum class BodySide { Right = 0, Left = 1 };
inline const char* sideName(BodySide s) { return s == BodySide::Right ? "right" : "left"; }
inline BodySide otherSide(BodySide s) { return s == BodySide::Right ? BodySide::Left : BodySide::Right; }

struct OpenSimRecording {
  OpenSimTable ik;   // IK .mot/.sto: pelvis_tilt, pelvis_tx, pelvis_ty, hip_flexion_r/l, knee_angle_r/l, lumbar_extension
  OpenSimTable grf;  // GRF .mot: <prefix>vx, vy, px, py per plate
  std::optional<TrcData> trc;  // markers for the trunk line and the belt speed
};

// Where the five links of a person lumped from an OpenSim model sit in that model's pelvis frame
// (x forward, y up at zero pelvis tilt): hip joint centre, pelvis CoM and the back joint [m],
// torso (+ head, arms) CoM [m] in the torso frame from the back joint, and the two masses [kg]
// whose sum is the trunk m3. Read from the robot file (io/pelvis_frame_file.hpp).
struct PelvisFrame {
  std::array<double, 2> hip{}, pelvis_com{}, back{}, torso_com{};
  double pelvis_mass = 0.0, torso_mass = 0.0;
};

struct OpenSimImportOptions {
  std::optional<double> belt_speed;  // [m/s], > 0 when the belt carries the feet towards −X
  double contact_threshold = 20.0;   // [N]: a foot is in contact while its vertical force exceeds it
  double cutoff_hz = 6.0;            // smoothing-spline gain 1/2 frequency (smoothing_spline.hpp)
  // Trunk line from the pelvis-to-shoulder markers when a .trc is given (the data README's
  // advice); false: through the IK model's lumped pelvis + torso CoM even with markers.
  bool trunk_from_markers = true;
  ConventionHints conventions;      // plates, knee sign, coordinate and marker names
  std::optional<std::pair<double, double>> time_window;  // [s], inclusive; none: the whole record
  std::optional<PelvisFrame> pelvis_frame;  // the robot's; required (hip and trunk geometry)
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
  Eigen::MatrixX2d cop;         // centre of pressure, belt removed [m] (meaningless without contact)
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
  // Median |horizontal heel-marker velocity| over mid single support after belt removal: a
  // foot at rest gives ~0; a wrong belt speed or a plate given to the wrong foot does not.
  std::optional<double> stance_heel_speed;
  std::string trunk_source;       // "markers", "IK model CoM"
  Eigen::MatrixXd q, qd, qdd;     // N × 5, (α, δ1, δ2, δ3, δ4) of (1.13) and derivatives
  Eigen::MatrixXd reactions;      // N × 4: R1x, R1z, R2x, R2z (gravity frame, on the robot)
  Eigen::MatrixX2d cop_x;         // N × 2: CoP x of leg 1, leg 2, belt removed; the ankle's x
                                  // (the point foot) while that leg carries no load [m]
  OpenSimConventions conventions; // as resolved, with how each was decided
  std::vector<std::string> notes; // samples dropped by the time window or the plate span
};

// Converts the samples inside the IK record and the time window, restricted to the longest span
// in which the plates see a foot (an overground trial's steps off the plates are dropped, with a
// note). Data that cannot be labelled (no contact, no single support for the belt estimate, no
// force-plate sample in the window, a missing column, conventions that cannot be resolved) are
// DataErrors naming the file. `robot` gives the thigh (l2) and shank (l1) lengths and
// options.pelvis_frame (the robot file's) the hip position and trunk geometry in the IK model's
// pelvis (none: refused, naming robot.source_file). The files are read by
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
