#pragma once
// Measured walker states built from pinned coordinates, for the walker's tests.
#include <array>

#include "gaitopt/control/walker.hpp"
#include "gaitopt/model/chain_kinematics.hpp"

namespace gaitopt::test {

// The measured state of pinned coordinates (q, q̇) with `leg1` the physical leg 1, foot 1 at x.
inline WalkerState measured(const Model& m, const Vec5& q, const Vec5& qd, Stance leg1, double x,
                            std::array<bool, 2> contact, double t) {
  WalkerState s;
  const ChainState<double> st = chainState(m, q, qd);
  s.t = t;
  s.hip = chainPoint(m.pinned.hip, st) + Vec2(x, 0.0);
  s.hip_rate = chainPointVelocity(m.pinned.hip, st);
  s.pitch = q(0) + q(1) - q(2);
  s.pitch_rate = qd(0) + qd(1) - qd(2);
  s.phi = physicalOrder(jointSpeeds(q), leg1);
  s.phi_rate = physicalOrder(jointSpeeds(qd), leg1);
  s.contact = contact;
  return s;
}

// The gait's SS state at α (on its virtual constraints, rate α̇).
inline void ssState(const GaitMotion<double>& mo, double alpha, double alphad, Vec5& q, Vec5& qd) {
  q(0) = alpha;
  qd(0) = alphad;
  for (int j = 0; j < 4; ++j) {
    q(j + 1) = mo.ss_path[j](alpha).value;
    qd(j + 1) = mo.ss_path[j](alpha).first * alphad;
  }
}

}  // namespace gaitopt::test
