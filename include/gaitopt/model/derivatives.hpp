#pragma once
// Exact first derivatives of the pinned model terms and of single-support inverse dynamics,
// obtained by running the templated model on a forward-mode AD scalar (Eigen's AutoDiff).
#include <array>

#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"

namespace gaitopt {

struct PinnedDerivatives {
  PinnedTerms<double> value;
  std::array<Mat5, 5> dA_dq;  // ∂A/∂q_k
  Mat5 dC_dq, dC_dqd, dG_dq;  // column k: ∂(·)/∂q_k
  std::array<Eigen::Matrix<double, 2, 5>, 5> dD2_dq;
  Eigen::Matrix<double, 2, 5> dH2_dq, dH2_dqd;
};

PinnedDerivatives pinnedTermsDerivatives(const Model& model, const Vec5& q, const Vec5& qd);

// Columns ordered [q (5), q̇ (5), q̈ (5)].
struct InverseDynamicsSSDerivatives {
  SingleSupportInverseDynamics<double> value;
  Eigen::Matrix<double, 4, 15> dgamma_star, dgamma;
  Eigen::Matrix<double, 1, 15> dalpha_row_residual;
  Eigen::Matrix<double, 2, 15> dR1;
};

InverseDynamicsSSDerivatives inverseDynamicsSSDerivatives(const Model& model, const Vec5& q,
                                                          const Vec5& qd, const Vec5& qdd,
                                                          SignMode mode);

}  // namespace gaitopt
