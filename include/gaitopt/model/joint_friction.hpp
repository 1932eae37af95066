#pragma once
// Joint friction (1.20), (1.21): Γ = Γ* − Γs sign(ω) − Fv ω with ω = D_Γᵀ q̇ the joint-side
// relative speeds. The smooth sign keeps torques differentiable in the gait parameters; the
// exact sign is for reporting.
#include <cmath>

#include "gaitopt/model/model.hpp"
#include "gaitopt/math/scalar.hpp"
#include "gaitopt/math/types.hpp"

namespace gaitopt {

enum class SignMode { Smooth, Exact };

// ω = D_Γᵀ q̇ = (δ̇1, −δ̇2, −(δ̇2 + δ̇3), δ̇4).
template <class S> Vector4<S> jointSpeeds(const Vector5<S>& qd) {
  return Vector4<S>(qd(1), -qd(2), -(qd(2) + qd(3)), qd(4));
}

template <class S> S frictionSign(const S& w, double width, SignMode mode) {
  using std::tanh;
  if (mode == SignMode::Smooth) return tanh(w / width);
  const double v = valueOf(w);
  return S(v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0));
}

// Γ* − Γ: the torque the motor must add to overcome friction (1.21).
template <class S>
Vector4<S> frictionTorque(const Model& model, const Vector4<S>& omega, SignMode mode) {
  Vector4<S> f;
  for (int j = 0; j < 4; ++j)
    f(j) = model.coulomb(j) * frictionSign(omega(j), model.options.friction_smoothing, mode) +
           model.viscous(j) * omega(j);
  return f;
}

}  // namespace gaitopt
