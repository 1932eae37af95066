#pragma once
// Algebraic rigid impact (2.1)/(2.13) with zero restitution and Coulomb friction on the
// post-impact velocities (Hurmuzlu–Marghitu form, Appendix C), one behaviour at a time.
//
// Contact space: V = [V1; V2] = D Ẋ with D = [D1; D2] (4×7), I = [I1; I2] the impulses, and
// W = D A⁻¹ Dᵀ (digest's corrected (2.13)). A behaviour fixes four linear equations in I;
// then V⁺ = V⁻ + W I and Ẋ⁺ = Ẋ⁻ + A⁻¹ Dᵀ I (2.1). Everything is linear in Ẋ⁻ given X and is
// templated on the scalar, so an AD scalar gives exact derivatives through the impact.
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <string>
#include <vector>

#include "gaitopt/math/scalar.hpp"
#include "gaitopt/math/types.hpp"
#include "gaitopt/model/dynamics_floating.hpp"

namespace gaitopt {

// slip+ = that foot's post-impact tangential velocity > 0 (toward +x), impulse I_x = −μ I_z.
enum class Foot1Behaviour { Lift, Stick, SlipPlus, SlipMinus };
enum class Foot2Behaviour { Stick, SlipPlus, SlipMinus };
struct ImpactBehaviour {
  Foot1Behaviour foot1;
  Foot2Behaviour foot2;
};
inline bool operator==(ImpactBehaviour a, ImpactBehaviour b) {
  return a.foot1 == b.foot1 && a.foot2 == b.foot2;
}
inline bool operator!=(ImpactBehaviour a, ImpactBehaviour b) { return !(a == b); }

// The 12 behaviours of Appendix C, foot 1 major.
std::vector<ImpactBehaviour> allImpactBehaviours();
const char* toString(Foot1Behaviour b);  // lift | stick | slip+ | slip-
const char* toString(Foot2Behaviour b);  // stick | slip+ | slip-

// What a slack measures, for normalising it (impulse [N·s] or velocity [m/s]).
enum class SlackKind { Impulse, Velocity };
struct SlackInfo {
  SlackKind kind;
  const char* name;  // e.g. "mu*I1z - I1x", "V1z+"
};
// The inequalities of a behaviour, in the order of ImpactOutcome::slacks.
std::vector<SlackInfo> impactSlacks(ImpactBehaviour behaviour);

template <class S> using Vector4S = Eigen::Matrix<S, 4, 1>;
template <class S> using Matrix4S = Eigen::Matrix<S, 4, 4>;

template <class S> struct ImpactOutcome {
  Vector7<S> Xd_plus;             // floating coordinates [q (5), x_t, z_t] after impact
  Vector2<S> impulse1, impulse2;  // world-frame impulses on foot 1 and foot 2 [N·s]
  S energy_loss;                  // kinetic energy before − after [J], ≥ 0
  Eigen::Matrix<S, Eigen::Dynamic, 1> slacks;  // the behaviour's inequalities, ≥ 0 if consistent
  Vector4S<S> V_plus;             // [V1+; V2+] foot velocities after impact [m/s]
};

// The quantities every behaviour shares at one configuration and pre-impact velocity: computed
// once, then each behaviour costs one 4×4 solve.
template <class S> struct ImpactSystem {
  Matrix7<S> A;
  Eigen::Matrix<S, 7, 4> Ainv_Dt;  // A⁻¹ Dᵀ
  Matrix4S<S> W;                   // D A⁻¹ Dᵀ (2.13)
  Vector4S<S> V_minus;             // [V1⁻; V2⁻]
  Vector7<S> Xd_minus;
};

template <class S>
ImpactSystem<S> impactSystem(const Model& model, const Vector7<S>& X, const Vector7<S>& Xd_minus) {
  const FloatingTerms<S> t = floatingTerms(model, X, Xd_minus);
  ImpactSystem<S> s;
  s.A = t.A;
  Eigen::Matrix<S, 4, 7> D;
  D << t.D1, t.D2;
  // A is symmetric positive definite (a kinetic-energy matrix): Cholesky, which runs on AD.
  s.Ainv_Dt = t.A.llt().solve(D.transpose());
  s.W = D * s.Ainv_Dt;
  s.V_minus = D * Xd_minus;
  s.Xd_minus = Xd_minus;
  return s;
}

namespace detail {

// Row of the equality set: W row `k` · I = −V⁻(k), i.e. the post-impact component k is 0.
template <class S>
void velocityZeroRow(const ImpactSystem<S>& s, int k, int row, Matrix4S<S>& M, Vector4S<S>& r) {
  M.row(row) = s.W.row(k);
  r(row) = -s.V_minus(k);
}

// Row I_x + sign μ I_z = 0 of the contact whose impulse starts at index `i0` (slip law).
template <class S>
void slipRow(int i0, double sign_mu, int row, Matrix4S<S>& M, Vector4S<S>& r) {
  M.row(row).setZero();
  M(row, i0) = S(1.0);
  M(row, i0 + 1) = S(sign_mu);
  r(row) = S(0.0);
}

template <class S>
void stickSlacks(const Vector4S<S>& I, int i0, double mu, std::vector<S>& out) {
  out.push_back(mu * I(i0 + 1) - I(i0));  // |I_x| ≤ μ I_z (2.10)/(2.12)
  out.push_back(mu * I(i0 + 1) + I(i0));
  out.push_back(I(i0 + 1));               // I_z ≥ 0 (implied by the cone only when μ > 0)
}

template <class S>
void slipSlacks(const Vector4S<S>& I, const Vector4S<S>& V, int i0, double direction,
                std::vector<S>& out) {
  out.push_back(I(i0 + 1));          // I_z ≥ 0 (2.9)/(2.11)
  out.push_back(direction * V(i0));  // V_x⁺ of the slip's sign
}

}  // namespace detail

// Equalities M I = r of one behaviour of Appendix C.
template <class S>
void impactEqualities(const ImpactSystem<S>& s, ImpactBehaviour b, double mu, Matrix4S<S>& M,
                      Vector4S<S>& r) {
  switch (b.foot1) {
    case Foot1Behaviour::Lift:  // I1 = 0 (2.5)
      M.template topRows<2>().setZero();
      M(0, 0) = M(1, 1) = S(1.0);
      r(0) = r(1) = S(0.0);
      break;
    case Foot1Behaviour::Stick:  // V1⁺ = 0 (2.10)
      detail::velocityZeroRow(s, 0, 0, M, r);
      detail::velocityZeroRow(s, 1, 1, M, r);
      break;
    case Foot1Behaviour::SlipPlus:  // V1z⁺ = 0, I1x = −μ I1z (2.9)
    case Foot1Behaviour::SlipMinus:
      detail::velocityZeroRow(s, 1, 0, M, r);
      detail::slipRow(0, b.foot1 == Foot1Behaviour::SlipPlus ? mu : -mu, 1, M, r);
      break;
  }
  switch (b.foot2) {
    case Foot2Behaviour::Stick:  // V2⁺ = 0 (2.12)
      detail::velocityZeroRow(s, 2, 2, M, r);
      detail::velocityZeroRow(s, 3, 3, M, r);
      break;
    case Foot2Behaviour::SlipPlus:  // V2z⁺ = 0 (2.2), I2x = −μ I2z (2.11)
    case Foot2Behaviour::SlipMinus:
      detail::velocityZeroRow(s, 3, 2, M, r);
      detail::slipRow(2, b.foot2 == Foot2Behaviour::SlipPlus ? mu : -mu, 3, M, r);
      break;
  }
}

// The behaviour's inequalities at impulses I and post-impact contact velocities V (order of
// impactSlacks).
template <class S>
Eigen::Matrix<S, Eigen::Dynamic, 1> impactSlackValues(const Vector4S<S>& I, const Vector4S<S>& V,
                                                      ImpactBehaviour b, double mu) {
  std::vector<S> out;
  switch (b.foot1) {
    case Foot1Behaviour::Lift: out.push_back(V(1)); break;  // V1z⁺ ≥ 0 (2.5)
    case Foot1Behaviour::Stick: detail::stickSlacks(I, 0, mu, out); break;
    case Foot1Behaviour::SlipPlus: detail::slipSlacks(I, V, 0, 1.0, out); break;
    case Foot1Behaviour::SlipMinus: detail::slipSlacks(I, V, 0, -1.0, out); break;
  }
  switch (b.foot2) {
    case Foot2Behaviour::Stick: detail::stickSlacks(I, 2, mu, out); break;
    case Foot2Behaviour::SlipPlus: detail::slipSlacks(I, V, 2, 1.0, out); break;
    case Foot2Behaviour::SlipMinus: detail::slipSlacks(I, V, 2, -1.0, out); break;
  }
  Eigen::Matrix<S, Eigen::Dynamic, 1> v(static_cast<Eigen::Index>(out.size()));
  for (std::size_t i = 0; i < out.size(); ++i) v(static_cast<Eigen::Index>(i)) = out[i];
  return v;
}

// One behaviour on a precomputed system. The 4×4 equality matrix is regular except on
// degenerate configurations (then the solve returns non-finite values, which the caller
// treats as "no solution of this behaviour").
template <class S>
ImpactOutcome<S> algebraicImpact(const ImpactSystem<S>& s, ImpactBehaviour behaviour, double mu) {
  Matrix4S<S> M;
  Vector4S<S> r;
  impactEqualities(s, behaviour, mu, M, r);
  const Vector4S<S> I = M.partialPivLu().solve(r);
  ImpactOutcome<S> o;
  o.V_plus = s.V_minus + s.W * I;
  o.Xd_plus = s.Xd_minus + s.Ainv_Dt * I;  // (2.1)
  o.impulse1 = I.template head<2>();
  o.impulse2 = I.template tail<2>();
  const S e_minus = 0.5 * s.Xd_minus.dot(s.A * s.Xd_minus);
  const S e_plus = 0.5 * o.Xd_plus.dot(s.A * o.Xd_plus);
  o.energy_loss = e_minus - e_plus;
  o.slacks = impactSlackValues(I, o.V_plus, behaviour, mu);
  return o;
}

// One behaviour of Appendix C: (2.1)/(2.13) with zero restitution and the behaviour's
// equalities; linear in Xd_minus given X, templated so AD gives exact derivatives through it.
template <class S>
ImpactOutcome<S> algebraicImpact(const Model& model, const Vector7<S>& X,
                                 const Vector7<S>& Xd_minus, ImpactBehaviour behaviour,
                                 double mu) {
  return algebraicImpact(impactSystem(model, X, Xd_minus), behaviour, mu);
}

}  // namespace gaitopt
