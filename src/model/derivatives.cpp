#include "gaitopt/model/derivatives.hpp"

#include <unsupported/Eigen/AutoDiff>

namespace gaitopt {
namespace {

template <int N> using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;

// Seeds x as AD variables number offset..offset+4 of N.
template <int N> Vector5<AD<N>> seed(const Vec5& x, int offset) {
  Vector5<AD<N>> out;
  for (int i = 0; i < 5; ++i) out(i) = AD<N>(x(i), N, offset + i);
  return out;
}

template <class Dense, int N>
auto values(const Eigen::MatrixBase<Dense>& m) {
  return m.unaryExpr([](const AD<N>& x) { return x.value(); }).eval();
}

}  // namespace

PinnedDerivatives pinnedTermsDerivatives(const Model& model, const Vec5& q, const Vec5& qd) {
  using S = AD<10>;
  const PinnedTerms<S> t = pinnedTerms(model, seed<10>(q, 0), seed<10>(qd, 5));
  PinnedDerivatives d;
  d.value.A = values<Matrix5<S>, 10>(t.A);
  d.value.C = values<Vector5<S>, 10>(t.C);
  d.value.G = values<Vector5<S>, 10>(t.G);
  d.value.foot2 = values<Vector2<S>, 10>(t.foot2);
  d.value.D2 = values<Matrix25<S>, 10>(t.D2);
  d.value.H2 = values<Vector2<S>, 10>(t.H2);
  d.value.com = values<Vector2<S>, 10>(t.com);
  d.value.com_velocity = values<Vector2<S>, 10>(t.com_velocity);
  for (int k = 0; k < 5; ++k) {
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) d.dA_dq[k](i, j) = t.A(i, j).derivatives()(k);
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 5; ++j) d.dD2_dq[k](i, j) = t.D2(i, j).derivatives()(k);
  }
  for (int i = 0; i < 5; ++i) {
    d.dC_dq.row(i) = t.C(i).derivatives().head<5>().transpose();
    d.dC_dqd.row(i) = t.C(i).derivatives().tail<5>().transpose();
    d.dG_dq.row(i) = t.G(i).derivatives().head<5>().transpose();
  }
  for (int i = 0; i < 2; ++i) {
    d.dH2_dq.row(i) = t.H2(i).derivatives().head<5>().transpose();
    d.dH2_dqd.row(i) = t.H2(i).derivatives().tail<5>().transpose();
  }
  return d;
}

InverseDynamicsSSDerivatives inverseDynamicsSSDerivatives(const Model& model, const Vec5& q,
                                                          const Vec5& qd, const Vec5& qdd,
                                                          SignMode mode) {
  using S = AD<15>;
  const SingleSupportInverseDynamics<S> r =
      inverseDynamicsSS(model, seed<15>(q, 0), seed<15>(qd, 5), seed<15>(qdd, 10), mode);
  InverseDynamicsSSDerivatives d;
  d.value.gamma_star = values<Vector4<S>, 15>(r.gamma_star);
  d.value.gamma = values<Vector4<S>, 15>(r.gamma);
  d.value.alpha_row_residual = r.alpha_row_residual.value();
  d.value.R1 = values<Vector2<S>, 15>(r.R1);
  for (int i = 0; i < 4; ++i) {
    d.dgamma_star.row(i) = r.gamma_star(i).derivatives().transpose();
    d.dgamma.row(i) = r.gamma(i).derivatives().transpose();
  }
  d.dalpha_row_residual = r.alpha_row_residual.derivatives().transpose();
  for (int i = 0; i < 2; ++i) d.dR1.row(i) = r.R1(i).derivatives().transpose();
  return d;
}

}  // namespace gaitopt
