#pragma once
// The full motion of a step at one instant of a phase: q, q̇, q̈, the motor torques Γ* (3.57)
// and the ground reactions, in the SS from a path point and the zero dynamics' rates, in the DS
// from the prescribed coordinates at a time with the force split (gait/ds_force_distribution.hpp).
#include <Eigen/LU>
#include <array>

#include "gaitopt/gait/boundary_geometry.hpp"
#include "gaitopt/gait/ds_force_distribution.hpp"
#include "gaitopt/gait/ds_path.hpp"
#include "gaitopt/gait/evaluation.hpp"
#include "gaitopt/gait/options.hpp"
#include "gaitopt/gait/zero_dynamics.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"

namespace gaitopt {

// The motion at one sample: q and its rates, Γ* and ω (joint side), the reactions under
// foot 1 (stance) and foot 2 (zero in the SS), the swing foot and the CoM.
template <class S> struct PhaseSample {
  int branch = 0;  // DS force-distribution formula (gait/ds_force_distribution.hpp)
  std::array<S, 6> switching{};
  Vector5<S> q, qd, qdd;
  Vector4<S> gamma_star, omega;
  Vector2<S> R1, R2, foot2, com;
};

// An SS sample at a path point with the zero dynamics' α̇, α̈ there.
template <class S>
PhaseSample<S> ssSample(const Model& m, const SsPathPoint<S>& pt, const S& alphadot,
                        const S& alphaddot) {
  PhaseSample<S> s;
  const S ad2 = alphadot * alphadot;
  s.q = pt.q;
  s.qd = pt.qs * alphadot;
  s.qdd = pt.qs * alphaddot + pt.qss * ad2;
  const Vector5<S> tau = pt.tau_a * alphaddot + pt.tau_c * ad2 + pt.G;
  s.omega = jointSpeeds(s.qd);
  s.gamma_star = solveDGamma25(Vector4<S>(tau.template tail<4>())) +
                 frictionTorque(m, s.omega, SignMode::Smooth);  // (3.57), (1.21)
  const Vector2<S> acc = pt.com_a * alphaddot + pt.com_c * ad2;
  s.R1 = Vector2<S>(m.total_mass * acc(0), m.total_mass * (acc(1) + m.gravity));  // (1.36)
  s.R2.setZero();
  s.foot2 = pt.foot2;
  s.com = pt.com;
  return s;
}

// The DS sample at time t from the DS start; forced_branch: the force split's formula, or
// kBranchFree for the optimal one.
template <class S>
PhaseSample<S> dsSample(const Model& m, const GaitOptions& o, const GaitMotion<S>& mo,
                        const S& t, int forced_branch = kBranchFree) {
  const DsPrescribed<S> pr = dsPrescribed(mo, t);
  PhaseSample<S> s;
  const Vector2<S> leg2 = leg2InverseKinematics(m, pr.alpha, pr.d1,
                                                rearFootFromHip(m, pr.alpha, pr.d1, mo.d));
  s.q = Vector5<S>(pr.alpha, pr.d1, pr.d2, leg2(0), leg2(1));
  ChainState<S> st = chainState(m, s.q, Vector5<S>(Vector5<S>::Zero()));
  const Matrix25<S> D2 = chainPointJacobian(m, m.pinned.foot2, st);
  Eigen::Matrix<S, 2, 2> D34;
  D34 << D2(0, 3), D2(0, 4), D2(1, 3), D2(1, 4);
  const Eigen::Matrix<S, 2, 2> D34inv = D34.inverse();
  const Vector2<S> v34 = -D34inv * (D2.col(0) * pr.alphad + D2.col(1) * pr.d1d);  // (1.34)
  s.qd = Vector5<S>(pr.alphad, pr.d1d, pr.d2d, v34(0), v34(1));
  st.theta_dot = constantTimes(m.theta_map, s.qd);
  const Vector2<S> H2 = chainPointBias(m.pinned.foot2, st);
  const Vector2<S> a34 = -D34inv * (D2.col(0) * pr.alphadd + D2.col(1) * pr.d1dd + H2);
  s.qdd = Vector5<S>(pr.alphadd, pr.d1dd, pr.d2dd, a34(0), a34(1));  // (1.35)
  const PinnedMotionForces<S> forces = pinnedMotionForces(m, st, s.qdd);
  const DoubleSupportAffine<S> aff = doubleSupportAffine(m, forces, s.qd, SignMode::Smooth);
  const double M = m.total_mass;
  const S R2z0 = aff.R2z0;                                          // (3.58)
  const S R1z0 = M * (aff.com_acceleration(1) + m.gravity) - R2z0;  // (3.59) corrected
  const DsBounds<S> bounds = r2xBounds(R1z0, R2z0, S(M * aff.com_acceleration(0)),
                                       o.friction_coefficient,
                                       forced_branch >= 0 ? forced_branch % 4 : kBranchFree);
  s.omega = jointSpeeds(s.qd);
  const DsChoice<S> choice = o.ds_distribution == DsDistribution::Torque
                                ? r2xMinTorque(aff.J, aff.K, bounds, forced_branch)
                                : r2xMinPower(aff.J, aff.K, s.omega, jouleCoefficient(m), bounds,
                                              forced_branch);
  const S& R2x = choice.r2x;
  s.branch = choice.branch;
  s.switching = choice.switching;
  s.gamma_star = aff.J - aff.K * R2x;  // (3.62)
  s.R2 = Vector2<S>(R2x, R2z0 + aff.R2z_slope * R2x);
  s.R1 = Vector2<S>(M * aff.com_acceleration(0), M * (aff.com_acceleration(1) + m.gravity)) - s.R2;
  s.foot2 = forces.foot2;
  s.com = forces.com;
  return s;
}

}  // namespace gaitopt
