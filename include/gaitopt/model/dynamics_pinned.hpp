#pragma once
// Pinned single-support model (1.32): foot 1 is a revolute joint at the origin,
// A(q) q̈ + C(q, q̇) + G(q) = D_Γ Γ + D2(q)ᵀ R2, with q = [α, δ1, δ2, δ3, δ4].
#include "gaitopt/model/chain_kinematics.hpp"

namespace gaitopt {

template <class S> struct PinnedTerms {
  Matrix5<S> A;
  Vector5<S> C, G;
  Vector2<S> foot2;   // X2 (1.38)
  Matrix25<S> D2;     // ∂X2/∂q
  Vector2<S> H2;      // Ḋ2 q̇ (1.35)
  Vector2<S> com;     // whole-body centre of mass
  Vector2<S> com_velocity;
};

template <class S>
PinnedTerms<S> pinnedTerms(const Model& model, const Vector5<S>& q, const Vector5<S>& qd) {
  const ChainState<S> st = chainState(model, q, qd);
  const ChainCoefficients& c = model.pinned;
  PinnedTerms<S> t;
  t.A = thetaCongruence(model, chainInertiaTheta(c, model.inertia, st));
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) t.A(i, j) += model.rotor_inertia_matrix(i, j);  // (1.17)
  t.C = constantTimes(model.theta_map_transpose, chainCoriolisTheta(c, st));
  t.G = constantTimes(model.theta_map_transpose, chainGravityTheta(c, model.gravity, st));
  t.foot2 = chainPoint(c.foot2, st);
  t.D2 = chainPointJacobian(model, c.foot2, st);
  t.H2 = chainPointBias(c.foot2, st);
  const double inv_m = 1.0 / model.total_mass;
  t.com = chainPoint(c.b, st) * inv_m;
  t.com_velocity = chainPointVelocity(c.b, st) * inv_m;
  return t;
}

// A v without forming A (= Tᵀ M_θ T + Σ I_mj w_j w_jᵀ): what a prescribed motion needs, at
// a fraction of the cost of the full matrix on an AD scalar.
template <class S>
Vector5<S> inertiaTimes(const Model& model, const Matrix5<S>& M_theta, const Vector5<S>& v) {
  const Vector5<S> theta_v = constantTimes(model.theta_map, v);
  Vector5<S> out = constantTimes(model.theta_map_transpose, Vector5<S>(M_theta * theta_v));
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      if (model.rotor_inertia_matrix(i, j) != 0.0) out(i) += model.rotor_inertia_matrix(i, j) * v(j);
  return out;
}

// Generalised forces of a motion at (q, q̇) for the accelerations q̈: A q̈ + C + G, from one
// chain state (one set of sines and cosines).
template <class S> struct PinnedMotionForces {
  Vector5<S> tau;          // A q̈ + C + G
  Matrix25<S> D2;          // ∂X2/∂q
  Vector2<S> foot2, H2, com, com_acceleration;
};

template <class S>
PinnedMotionForces<S> pinnedMotionForces(const Model& model, const ChainState<S>& st,
                                         const Vector5<S>& qdd) {
  const ChainCoefficients& c = model.pinned;
  const Matrix5<S> Mt = chainInertiaTheta(c, model.inertia, st);
  PinnedMotionForces<S> f;
  f.tau = inertiaTimes(model, Mt, qdd) +
          constantTimes(model.theta_map_transpose, chainCoriolisTheta(c, st)) +
          constantTimes(model.theta_map_transpose, chainGravityTheta(c, model.gravity, st));
  f.D2 = chainPointJacobian(model, c.foot2, st);
  f.foot2 = chainPoint(c.foot2, st);
  f.H2 = chainPointBias(c.foot2, st);
  const double inv_m = 1.0 / model.total_mass;
  f.com = chainPoint(c.b, st) * inv_m;
  f.com_acceleration =
      chainPointAcceleration(c.b, st, constantTimes(model.theta_map, qdd)) * inv_m;
  return f;
}

// Whole-body CoM acceleration for given q̈ (Newton equations (1.36)).
template <class S>
Vector2<S> pinnedComAcceleration(const Model& model, const Vector5<S>& q, const Vector5<S>& qd,
                                 const Vector5<S>& qdd) {
  const ChainState<S> st = chainState(model, q, qd);
  return chainPointAcceleration(model.pinned.b, st, constantTimes(model.theta_map, qdd)) *
         (1.0 / model.total_mass);
}

// Angular momentum about foot 1: the α-row of the inertia matrix times q̇ (σ in (3.10)).
template <class S>
S angularMomentumFoot1(const PinnedTerms<S>& t, const Vector5<S>& qd) {
  return t.A.row(0).dot(qd);
}

template <class S> Vector2<S> pinnedHip(const Model& model, const Vector5<S>& q) {
  return chainPoint(model.pinned.hip, chainState(model, q, Vector5<S>(Vector5<S>::Zero())));
}

}  // namespace gaitopt
