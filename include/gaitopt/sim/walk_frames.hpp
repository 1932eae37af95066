#pragma once
// A closed-loop walk's samples placed in the world: each sample is in the frame of its stance
// foot (foot 1 at the origin); the stance foot advances to where the swing foot landed at the
// first DS sample after an SS, and the physical leg carried as leg 1 alternates each phase
// change (in DS leg 1 is the front leg).
#include <vector>

#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/sim/hybrid_walk.hpp"

namespace gaitopt {

struct WalkFrame {
  // The sample's time, phase and motion, with the swing (SS) or rear (DS) foot and the centre
  // of mass in the stance foot's frame; the drawing aids keep their defaults.
  TrajectoryRow row;
  int step = 0;
  bool first_leg_stance = true;  // leg 1 is the physical leg carried as leg 1 at the first SS
  double foot1_x = 0.0;          // stance foot abscissa, the first stance foot at 0
};

// The frames of every sample of `walk` on the plant model `plant`.
std::vector<WalkFrame> walkFrames(const Model& plant, const WalkResult& walk);

}  // namespace gaitopt
