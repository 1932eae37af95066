#pragma once
// Kinematics and Lagrangian terms of the planar five-body chain written in the absolute body
// angles θ = T q + c (1.13). Every point is origin + Σ_k e_k u(θ_k), so positions, Jacobians,
// the inertia matrix, Coriolis and gravity terms all reduce to sums over cos θ_k, sin θ_k.
#include <cmath>

#include "gaitopt/model/model.hpp"
#include "gaitopt/math/types.hpp"

namespace gaitopt {

template <class S> struct ChainState {
  Vector5<S> cos_theta, sin_theta, theta_dot;
};

template <class S>
ChainState<S> chainState(const Model& model, const Vector5<S>& q, const Vector5<S>& qd) {
  using std::cos;
  using std::sin;
  ChainState<S> st;
  const Vector5<S> theta = constantTimes(model.theta_map, q);
  st.theta_dot = constantTimes(model.theta_map, qd);
  for (int k = 0; k < 5; ++k) {
    const S th = theta(k) + model.theta_offset(k);
    st.cos_theta(k) = cos(th);
    st.sin_theta(k) = sin(th);
  }
  return st;
}

template <class S> Vector2<S> chainPoint(const Vec5& e, const ChainState<S>& st) {
  Vector2<S> p(S(0.0), S(0.0));
  for (int k = 0; k < 5; ++k)
    if (e(k) != 0.0) {
      p(0) += e(k) * st.cos_theta(k);
      p(1) += e(k) * st.sin_theta(k);
    }
  return p;
}

// ∂p/∂q = Σ_k e_k u'(θ_k) T_k, with u'(θ) = (−sin θ, cos θ).
template <class S>
Matrix25<S> chainPointJacobian(const Model& model, const Vec5& e, const ChainState<S>& st) {
  Eigen::Matrix<S, 2, 5> dtheta;
  for (int k = 0; k < 5; ++k) {
    dtheta(0, k) = -e(k) * st.sin_theta(k);
    dtheta(1, k) = e(k) * st.cos_theta(k);
  }
  Matrix25<S> J;
  for (int r = 0; r < 2; ++r)
    for (int j = 0; j < 5; ++j) {
      S acc(0.0);
      for (int k = 0; k < 5; ++k)
        if (model.theta_map(k, j) != 0.0) acc += model.theta_map(k, j) * dtheta(r, k);
      J(r, j) = acc;
    }
  return J;
}

// Velocity of the point, Σ_k e_k u'(θ_k) θ̇_k.
template <class S> Vector2<S> chainPointVelocity(const Vec5& e, const ChainState<S>& st) {
  Vector2<S> v(S(0.0), S(0.0));
  for (int k = 0; k < 5; ++k) {
    v(0) -= e(k) * st.sin_theta(k) * st.theta_dot(k);
    v(1) += e(k) * st.cos_theta(k) * st.theta_dot(k);
  }
  return v;
}

// J̇ q̇ = −Σ_k e_k u(θ_k) θ̇_k² (H in (1.6), (1.7), (1.35)).
template <class S> Vector2<S> chainPointBias(const Vec5& e, const ChainState<S>& st) {
  Vector2<S> h(S(0.0), S(0.0));
  for (int k = 0; k < 5; ++k) {
    const S w2 = st.theta_dot(k) * st.theta_dot(k);
    h(0) -= e(k) * st.cos_theta(k) * w2;
    h(1) -= e(k) * st.sin_theta(k) * w2;
  }
  return h;
}

// Acceleration of the point given θ̈: J θ̈ + bias.
template <class S>
Vector2<S> chainPointAcceleration(const Vec5& e, const ChainState<S>& st,
                                  const Vector5<S>& theta_ddot) {
  Vector2<S> a = chainPointBias(e, st);
  for (int k = 0; k < 5; ++k) {
    a(0) -= e(k) * st.sin_theta(k) * theta_ddot(k);
    a(1) += e(k) * st.cos_theta(k) * theta_ddot(k);
  }
  return a;
}

// M_θ(k,l) = P_kl cos(θ_k − θ_l) + δ_kl I_k (kinetic energy (1.16) in θ-coordinates).
template <class S>
Matrix5<S> chainInertiaTheta(const ChainCoefficients& c, const Vec5& inertia,
                             const ChainState<S>& st) {
  Matrix5<S> M;
  for (int k = 0; k < 5; ++k) {
    M(k, k) = S(c.P(k, k) + inertia(k));
    for (int l = k + 1; l < 5; ++l) {
      const S ckl = st.cos_theta(k) * st.cos_theta(l) + st.sin_theta(k) * st.sin_theta(l);
      M(k, l) = c.P(k, l) * ckl;
      M(l, k) = M(k, l);
    }
  }
  return M;
}

// Lagrange's d/dt ∂E/∂θ̇ − ∂E/∂θ velocity terms: h_k = Σ_l P_kl sin(θ_k − θ_l) θ̇_l².
template <class S> Vector5<S> chainCoriolisTheta(const ChainCoefficients& c, const ChainState<S>& st) {
  Vector5<S> h;
  for (int k = 0; k < 5; ++k) {
    S acc(0.0);
    for (int l = 0; l < 5; ++l) {
      if (l == k) continue;
      const S skl = st.sin_theta(k) * st.cos_theta(l) - st.cos_theta(k) * st.sin_theta(l);
      acc += c.P(k, l) * skl * st.theta_dot(l) * st.theta_dot(l);
    }
    h(k) = acc;
  }
  return h;
}

// ∂E_p/∂θ_k for E_p = g Σ_k b_k sin θ_k (1.18).
template <class S>
Vector5<S> chainGravityTheta(const ChainCoefficients& c, double g, const ChainState<S>& st) {
  Vector5<S> G;
  for (int k = 0; k < 5; ++k) G(k) = g * c.b(k) * st.cos_theta(k);
  return G;
}

// Tᵀ X T for the constant θ-map (inertia in q-coordinates from inertia in θ-coordinates).
template <class S> Matrix5<S> thetaCongruence(const Model& model, const Matrix5<S>& X) {
  const Matrix5<S> XT = constantTimes(model.theta_map_transpose, Matrix5<S>(X.transpose()))
                            .transpose();
  return constantTimes(model.theta_map_transpose, XT);
}

}  // namespace gaitopt
