#pragma once
// Floating 7-DOF model (1.1): X = [q, x_t, z_t] with (x_t, z_t) the trunk centre of mass,
// A(q) Ẍ + C(q, q̇) + G(X) = D_Γ Γ + D1ᵀ R1 + D2ᵀ R2.
#include "gaitopt/model/chain_kinematics.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"

namespace gaitopt {

template <class S> struct FloatingTerms {
  Vector7<S> X, Xd;
  Matrix7<S> A;
  Vector7<S> C, G;
  Matrix27<S> D1, D2;
  Vector2<S> H1, H2;
};

namespace detail {
template <class S>
Matrix27<S> floatingFootJacobian(const Model& model, const Vec5& e, const ChainState<S>& st) {
  Matrix27<S> D;
  D.template leftCols<5>() = chainPointJacobian(model, e, st);
  D.template rightCols<2>().setIdentity();
  return D;
}
}  // namespace detail

// The terms depend on q and q̇ only: the trunk position enters the potential linearly.
template <class S>
FloatingTerms<S> floatingTerms(const Model& model, const Vector7<S>& X, const Vector7<S>& Xd) {
  const Vector5<S> q = X.template head<5>(), qd = Xd.template head<5>();
  const ChainState<S> st = chainState(model, q, qd);
  const ChainCoefficients& c = model.floating;
  const double M = model.total_mass;
  FloatingTerms<S> t;
  t.X = X;
  t.Xd = Xd;
  t.A.setZero();
  t.A.template topLeftCorner<5, 5>() =
      thetaCongruence(model, chainInertiaTheta(c, model.inertia, st));
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) t.A(i, j) += model.rotor_inertia_matrix(i, j);
  // Coupling of trunk translation with rotations: ∂²E/∂θ̇_k∂ẋ_t = b_k u'(θ_k), mapped by T.
  const Matrix25<S> B = chainPointJacobian(model, c.b, st);
  t.A.template block<5, 2>(0, 5) = B.transpose();
  t.A.template block<2, 5>(5, 0) = B;
  t.A(5, 5) = t.A(6, 6) = S(M);
  t.C.template head<5>() = constantTimes(model.theta_map_transpose, chainCoriolisTheta(c, st));
  t.C.template tail<2>() = chainPointBias(c.b, st);  // d/dt of Σ b_k u'(θ_k) θ̇_k
  t.G.template head<5>() =
      constantTimes(model.theta_map_transpose, chainGravityTheta(c, model.gravity, st));
  t.G(5) = S(0.0);
  t.G(6) = S(M * model.gravity);
  t.D1 = detail::floatingFootJacobian(model, c.foot1, st);
  t.D2 = detail::floatingFootJacobian(model, c.foot2, st);
  t.H1 = chainPointBias(c.foot1, st);
  t.H2 = chainPointBias(c.foot2, st);
  return t;
}

// Floating state consistent with foot 1 at rest at the origin: X_t and Ẋ_t of the trunk CoM
// from the pinned kinematics.
template <class S>
void floatingStateFromPinned(const Model& model, const Vector5<S>& q, const Vector5<S>& qd,
                             Vector7<S>& X, Vector7<S>& Xd) {
  const ChainState<S> st = chainState(model, q, qd);
  const Vec5 trunk = model.pinned.body.row(2).transpose();
  X << q, chainPoint(trunk, st);
  Xd << qd, chainPointVelocity(trunk, st);
}

}  // namespace gaitopt
