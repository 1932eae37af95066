#pragma once
// A five-link robot (model/robot_params.hpp) lumped from an OpenSim model in the sagittal
// plane (OpenSim's x forward, y up) with every coordinate at zero (coupled ones at their
// couplers' values): each leg is split at the
// knee into a femur (the thigh body and whatever hangs on it but the shank, e.g. a patella)
// and a tibia (the shank with the whole foot, rigid at zero ankle, subtalar and toe angles);
// the trunk is every other body (pelvis, torso, arms, head). Per lump: masses summed, the
// CoM by the mass-weighted mean, the planar inertia Izz about that CoM by the parallel-axis
// theorem; the link is the line between its joint centres (hip to knee, knee to ankle), and
// the CoM's offset off that line is dropped (the five-link model keeps every CoM on its link
// axis). The trunk's axis is the hip-to-CoM line, so s3 is the hip-to-CoM distance. The legs
// are averaged (the five-link model is symmetric); the "point foot" is the ankle centre.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "gaitopt/ident/opensim_import.hpp"
#include "gaitopt/ident/osim_model.hpp"
#include "gaitopt/model/robot_params.hpp"

namespace gaitopt {

// One lumped link.
struct OsimLink {
  std::vector<std::string> bodies;
  double mass = 0.0;
  double length = 0.0;      // between its joint centres, sagittal (tibia, femur); 0 for the trunk
  double com = 0.0;         // CoM along the link from its proximal joint (s)
  double com_normal = 0.0;  // CoM off the link axis, + forward of it (dropped)
  double inertia = 0.0;     // Izz about the CoM
};

struct OsimLumping {
  std::array<OsimLink, 2> tibia, femur;  // [0] the first thigh named (right), [1] the other
  OsimLink trunk;
  double trunk_com_forward = 0.0, trunk_com_up = 0.0;  // trunk CoM from the hip midpoint
  double out_of_plane = 0.0;  // largest |z| between a leg's joint centres (dropped)
  double model_mass = 0.0;    // every body of the model
  double gravity = 0.0;       // |g| of the model
  double asymmetry = 0.0;     // largest |right − left| / mean over the leg quantities
  std::string asymmetry_quantity;  // e.g. "femur length"
  RobotParams robot;               // legs averaged, no motors, no friction, no bar
  // The hip (first thigh), the back joint and the two trunk lumps in the frame of the body the
  // thighs hang from, the geometry import-opensim places the links with; none when the thighs
  // hang from ground or that body carries no other body (no back joint).
  std::optional<PelvisFrame> pelvis_frame;
};

// Lumps `model` with the thighs named `thighs` (right, left). Throws DataError (the model's
// file, body or joint name, line) when a thigh is missing or not a child of the trunk, a
// shank has no foot joint, a lump has no mass or inertia, or gravity is not along −y.
OsimLumping lumpOsimModel(const OsimModel& model, const std::array<std::string, 2>& thighs = {"femur_r", "femur_l"});

}  // namespace gaitopt
