#include "gaitopt/sim/walk_frames.hpp"

#include "gaitopt/model/chain_kinematics.hpp"

namespace gaitopt {

std::vector<WalkFrame> walkFrames(const Model& plant, const WalkResult& r) {
  std::vector<WalkFrame> frames;
  double foot1_x = 0.0, next_foot1_x = 0.0;
  for (const WalkSample& s : r.samples) {
    const ChainState<double> st = chainState(plant, s.q, s.qd);
    const Vec2 foot2 = chainPoint(plant.pinned.foot2, st);
    if (s.single_support) next_foot1_x = foot1_x + foot2(0);  // where the swing foot lands
    if (!s.single_support && !frames.empty() &&
        frames.back().row.phase == Phase::SingleSupport)
      foot1_x = next_foot1_x;
    WalkFrame f;
    f.row = motionRow(s.t, s.single_support ? Phase::SingleSupport : Phase::DoubleSupport, s);
    f.row.foot2 = foot2;
    f.row.com = chainPoint(plant.pinned.b, st) / plant.total_mass;
    f.step = s.step;
    f.first_leg_stance = (s.step % 2 == 0) == s.single_support;
    f.foot1_x = foot1_x;
    frames.push_back(f);
  }
  return frames;
}

}  // namespace gaitopt
