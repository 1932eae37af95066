#pragma once
// The stance foot as a rolling arc of radius r (`gaitopt diagnose`'s `rocker_foot`), fixed to
// the stance tibia: its centre lies r above the thesis' point foot (the ankle), moved forward
// by an optional offset; the arc rolls without slipping on the ground line, so the contact point
// advances by r per radian the tibia turns forward (α decreases, (1.13)). At r = offset = 0 the
// model is the thesis' pinned one.
//
// Single-support equations written in the frame translating with the ankle: the pinned
// equations (1.32) hold there with the inertial force −m_i a_A on every body (a_A the ankle's
// acceleration), i.e. A q̈ + C + G + J_bᵀ a_A = D_Γ Γ + T₁ᵀ ((P − A) × R), J_b the Jacobian of
// Σ m_i p_i, R the ground reaction and (P − A) × R its moment about the ankle on the tibia.
// R itself is M (a_A + a_G) + M g (Newton (1.36), a_G the CoM acceleration in the ankle frame).
// The exact rolling dynamics; synth checks them against the floating model (1.1).
#include <cmath>

#include "gaitopt/model/dynamics_pinned.hpp"

namespace gaitopt {

template <class S> struct RockerContact {
  Vector2<S> ankle_acceleration;  // a_A [m/s²], gravity frame
  Vector2<S> contact_arm;         // P − A, contact point relative to the ankle [m]
  Vector2<S> ankle_jacobian;      // ∂A/∂α [m/rad] (a_A = ∂A/∂α α̈ + ∂²A/∂α² α̇²)
};

// Rolling contact at stance-tibia angle α (gravity frame) on a ground inclined by `slope`
// (+ uphill), for an arc of radius r whose lowest point lies `offset` ahead of the ankle when
// the tibia is perpendicular to the ground (0: below the ankle). In the ground frame, with
// β = α − slope, e = (−sin β, cos β) the tibia's direction, e⊥ = (cos β, sin β) its forward
// normal and n = (0, 1): centre C = A + r e + offset e⊥ at height r, rolling x_C = x0 − r β, so
// P − A = r (e − n) + offset e⊥, ∂A/∂β = (P − A) turned by −90° and ∂²A/∂β² = P − A + r n.
template <class S>
RockerContact<S> rockerContact(double radius, double offset, double slope, const S& alpha,
                               const S& alphad, const S& alphadd) {
  using std::cos;
  using std::sin;
  const S beta = alpha - slope;
  const S c = cos(beta), s = sin(beta);
  const Vector2<S> arm(-radius * s + offset * c, radius * (c - 1.0) + offset * s);
  const Vector2<S> d1(arm(1), -arm(0)), d2(arm(0), arm(1) + radius);
  const Vector2<S> acc = d1 * alphadd + d2 * (alphad * alphad);
  const double cs = std::cos(slope), ss = std::sin(slope);
  const auto rotate = [&](const Vector2<S>& v) {
    return Vector2<S>(cs * v(0) - ss * v(1), ss * v(0) + cs * v(1));
  };
  return {rotate(acc), rotate(arm), rotate(d1)};
}

template <class S> struct RockerForces {
  Vector5<S> tau;      // generalised force the joints must supply; tau(0) = α-row residual
  Vector2<S> reaction; // ground reaction R1 [N]
};

// The rocker single-support equations at a chain state, from the pinned motion forces (whose
// CoM acceleration is relative to the ankle).
template <class S>
RockerForces<S> rockerForces(const Model& model, const ChainState<S>& st,
                             const PinnedMotionForces<S>& f, const RockerContact<S>& c) {
  const double M = model.total_mass;
  RockerForces<S> r;
  const Matrix25<S> Jb = chainPointJacobian(model, model.pinned.b, st);
  r.reaction = (c.ankle_acceleration + f.com_acceleration) * M;
  r.reaction(1) += M * model.gravity;
  const S moment = c.contact_arm(0) * r.reaction(1) - c.contact_arm(1) * r.reaction(0);
  r.tau = f.tau + Jb.transpose() * c.ankle_acceleration;
  for (int j = 0; j < 5; ++j) r.tau(j) -= model.theta_map(0, j) * moment;  // T₁ᵀ (tibia 1)
  return r;
}

}  // namespace gaitopt
