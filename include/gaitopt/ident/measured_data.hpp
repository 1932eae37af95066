#pragma once
// Measured walking data: per sample the time, the measured coordinates, the phase, which
// physical leg is leg 1, the step number and, when measured, the joint-side motor torques Γ*
// and the ground reactions. Read from and written to CSV by io/measured_data.hpp.
#include <array>
#include <vector>

#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/model/stance.hpp"

namespace gaitopt {

struct MeasuredData {
  std::vector<double> t;
  std::vector<Vec5> q;  // α, δ1..δ4 as measured
  std::vector<Phase> phase;
  std::vector<Stance> stance;
  std::vector<long> step;
  bool has_torque = false, has_reactions = false;
  std::vector<Vec4> gamma;      // when has_torque
  std::vector<Vec4> reactions;  // R1x, R1z, R2x, R2z, when has_reactions
  // cop1x, cop2x when has_cop: world x [m] (gravity frame, as R1x) of the centre of pressure
  // of leg 1 and leg 2; a leg that carries no load has its point foot's x.
  bool has_cop = false;
  std::vector<std::array<double, 2>> cop;
  std::size_t size() const { return t.size(); }
};

}  // namespace gaitopt
