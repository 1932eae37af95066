#pragma once
// Fixtures of the impact tests: double-support configurations built from (α, δ1, θ3, step),
// and pre-impact floating states with foot 1 at rest.
#include "gaitopt/gait/leg_geometry.hpp"
#include "gaitopt/model/dynamics_floating.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"

namespace gaitopt::test {

// Foot 1 at the origin, foot 2 at (step, 0), trunk at absolute angle theta3 (π/2 = upright),
// leg 2 knee bent like a human's.
inline Vec5 doubleSupportQ(const Model& m, double alpha, double delta1, double theta3,
                           double step) {
  const Vec2 hip = -foot1FromHip(m, alpha, delta1);
  const Vec2 d34 = leg2InverseKinematics(m, alpha, delta1, Vec2(Vec2(step, 0.0) - hip));
  return Vec5(alpha, delta1, delta2FromTheta3(alpha, delta1, theta3), d34(0), d34(1));
}

// A walking-like double-support configuration: rear leg 1 inclined 0.4 rad, knees flexed, step 0.38 m.
inline Vec5 walkingImpactQ(const Model& m) {
  return doubleSupportQ(m, -0.4, -M_PI + 0.3, 0.5 * M_PI + 0.1, 0.38);
}

struct FloatingState {
  Vector7<double> X, Xd;
};

// Floating state with foot 1 at rest and pinned velocities qd.
inline FloatingState floatingState(const Model& m, const Vec5& q, const Vec5& qd) {
  FloatingState s;
  floatingStateFromPinned(m, q, qd, s.X, s.Xd);
  return s;
}

// Pinned velocities giving foot 2 the velocity v2 (least-norm joint speeds, α̇ included).
inline Vec5 pinnedVelocityForFoot2(const Model& m, const Vec5& q, const Vec2& v2) {
  const PinnedTerms<double> t = pinnedTerms(m, q, Vec5(Vec5::Zero()));
  return t.D2.transpose() * (t.D2 * t.D2.transpose()).ldlt().solve(v2);
}

}  // namespace gaitopt::test
