#pragma once
// Inverse dynamics of the pinned model in single support (rows 2–5 of (1.32), (3.57)) and in
// double support (one-parameter family in R2x, (3.58)–(3.62)).
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/joint_friction.hpp"

namespace gaitopt {

// Γ = D_Γ25⁻¹ v for v = rows 2–5 of the generalised force (digest §1.4).
template <class S> Vector4<S> solveDGamma25(const Vector4<S>& v) {
  return Vector4<S>(v(0), -v(1) + v(2), -v(2), v(3));
}

template <class S> struct SingleSupportInverseDynamics {
  Vector4<S> gamma_star;  // before friction (criteria, limits)
  Vector4<S> gamma;       // after friction (acts on the links)
  S alpha_row_residual;   // moment the point foot would have to supply; 0 if consistent
  Vector2<S> R1;          // foot-1 reaction from (1.36) with gravity
};

template <class S>
SingleSupportInverseDynamics<S> inverseDynamicsSS(const Model& model, const Vector5<S>& q,
                                                  const Vector5<S>& qd, const Vector5<S>& qdd,
                                                  SignMode mode) {
  const PinnedTerms<S> t = pinnedTerms(model, q, qd);
  const Vector5<S> tau = t.A * qdd + t.C + t.G;
  SingleSupportInverseDynamics<S> r;
  r.alpha_row_residual = tau(0);
  r.gamma = solveDGamma25(Vector4<S>(tau.template tail<4>()));
  r.gamma_star = r.gamma + frictionTorque(model, jointSpeeds(qd), mode);
  const Vector2<S> acc = pinnedComAcceleration(model, q, qd, qdd);
  const double M = model.total_mass;
  r.R1 = Vector2<S>(M * acc(0), M * (acc(1) + model.gravity));  // (1.36), corrected
  return r;
}

// Double support: Γ* = J − K R2x and R2z = R2z0 + R2z_slope R2x (α-row, (3.58)); R1 from the
// whole-body Newton equations (3.59).
template <class S> struct DoubleSupportAffine {
  Vector4<S> J, K;
  S R2z0, R2z_slope;
  Vector2<S> com_acceleration;
};

// From the generalised forces of the motion (A q̈ + C + G and the foot-2 Jacobian).
template <class S>
DoubleSupportAffine<S> doubleSupportAffine(const Model& model, const PinnedMotionForces<S>& f,
                                           const Vector5<S>& qd, SignMode mode) {
  DoubleSupportAffine<S> r;
  // α-row: τ1 = D2(0,0) R2x + D2(1,0) R2z, with D2(·,0) = (−z2, x2).
  r.R2z0 = f.tau(0) / f.D2(1, 0);
  r.R2z_slope = -f.D2(0, 0) / f.D2(1, 0);
  const Vector4<S> d2x = f.D2.row(0).template tail<4>().transpose();
  const Vector4<S> d2z = f.D2.row(1).template tail<4>().transpose();
  r.J = solveDGamma25(Vector4<S>(f.tau.template tail<4>() - d2z * r.R2z0)) +
        frictionTorque(model, jointSpeeds(qd), mode);
  r.K = solveDGamma25(Vector4<S>(d2x + d2z * r.R2z_slope));
  r.com_acceleration = f.com_acceleration;
  return r;
}

template <class S>
DoubleSupportAffine<S> doubleSupportAffine(const Model& model, const Vector5<S>& q,
                                           const Vector5<S>& qd, const Vector5<S>& qdd,
                                           SignMode mode) {
  return doubleSupportAffine(model, pinnedMotionForces(model, chainState(model, q, qd), qdd), qd,
                             mode);
}

template <class S> struct DoubleSupportInverseDynamics {
  Vector4<S> gamma_star, gamma;
  Vector2<S> R1, R2;
};

template <class S>
DoubleSupportInverseDynamics<S> inverseDynamicsDS(const Model& model, const Vector5<S>& q,
                                                  const Vector5<S>& qd, const Vector5<S>& qdd,
                                                  const S& R2x, SignMode mode) {
  const DoubleSupportAffine<S> a = doubleSupportAffine(model, q, qd, qdd, mode);
  DoubleSupportInverseDynamics<S> r;
  r.gamma_star = a.J - a.K * R2x;
  r.gamma = r.gamma_star - frictionTorque(model, jointSpeeds(qd), mode);
  r.R2 = Vector2<S>(R2x, a.R2z0 + a.R2z_slope * R2x);
  const double M = model.total_mass;
  r.R1 = Vector2<S>(M * a.com_acceleration(0), M * (a.com_acceleration(1) + model.gravity)) - r.R2;
  return r;
}

}  // namespace gaitopt
