#pragma once
// Fixtures of the impact tests: double-support configurations built from (α, δ1, θ3, step),
// and pre-impact floating states with foot 1 at rest.
#include "gaitopt/gait/leg_geometry.hpp"
#include "gaitopt/model/dynamics_floating.hpp"
#include "gaitopt/impact/impact_map.hpp"

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

// A generic two-contact mechanical system (not RABBIT): mass matrix A = identity (7×7) and
// contact Jacobian D = [L 0] (4×7), so W = L Lᵀ; foot 1 at rest, foot 2 arriving at angle theta.
// Used where RABBIT has no known example (Appendix B's indeterminacy, an accumulation).
inline ImpactSystem<double> genericSystem(const Eigen::Matrix4d& L, double theta) {
  ImpactSystem<double> s;
  s.A.setIdentity();
  s.Ainv_Dt.setZero();
  s.Ainv_Dt.topRows<4>() = L.transpose();
  s.W = L * L.transpose();
  s.V_minus << 0.0, 0.0, std::cos(theta), std::sin(theta);
  s.Xd_minus.setZero();
  s.Xd_minus.head<4>() = L.lu().solve(s.V_minus);
  return s;
}

// The legs-spread configuration of §2.4.6 (Fig. 2.9, whose numbers are lost): rear leg 1
// straight (δ1 = −π) inclined α = −1 rad, trunk horizontal pointing forward (θ3 = 0), feet
// 1.10 m apart, which bends the impacting leg 2 (δ4 ≈ −98.8°).
inline Vec5 legsSpreadQ(const Model& m) { return doubleSupportQ(m, -1.0, -M_PI, 0.0, 1.10); }

}  // namespace gaitopt::test
