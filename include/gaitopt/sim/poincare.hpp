#pragma once
// Poincaré analysis of a step-to-step map P: the Jacobian at a fixed point by central finite
// differences, its eigenvalues and dominant eigenvector, and the thesis' power iteration (4.61)
// on the map itself. The walking map takes the state (q, q̇) at single-support start to the
// state at the next single-support start (after DS and lift-off) in closed loop.
#include <Eigen/Core>
#include <functional>
#include <string>

#include "gaitopt/sim/hybrid_walk.hpp"

namespace gaitopt {

using StepMap = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

struct PoincareLinearisation {
  Eigen::MatrixXd jacobian;
  Eigen::VectorXcd eigenvalues;      // by decreasing modulus
  Eigen::VectorXcd dominant_vector;  // unit norm
  double fixed_point_residual = 0.0; // ‖P(x) − x‖∞ at the point linearised
};

// Central differences with steps h_i: column i = (P(x + h_i e_i) − P(x − h_i e_i)) / (2 h_i).
Eigen::MatrixXd finiteDifferenceJacobian(const StepMap& P, const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& h);

// Eigenvalues (by decreasing modulus) and dominant eigenvector of a map's Jacobian J.
PoincareLinearisation analyseJacobian(const Eigen::MatrixXd& J);

PoincareLinearisation linearisePoincare(const StepMap& P, const Eigen::VectorXd& x,
                                        const Eigen::VectorXd& h);

// `sensitivity()` (the variational equations), or central differences of P at x with steps h
// when CVODE cannot integrate those (IntegrationError, whose message goes to `fallback`; it is
// left unchanged otherwise).
PoincareLinearisation linearisePoincareOrDifferences(
    const std::function<PoincareLinearisation()>& sensitivity, const StepMap& P,
    const Eigen::VectorXd& x, const Eigen::VectorXd& h, std::string& fallback);

// (4.61): Δx_{k+1} = g(Δx_k)/c_{k+1}, g(Δx) = P(x + Δx) − P(x), c the signed largest
// component of g relative to the box Δx_max; returns c after `iterations`, `vector` Δx.
double powerIteration(const StepMap& P, const Eigen::VectorXd& x, const Eigen::VectorXd& dx_max,
                      int iterations, Eigen::VectorXd& vector);

// x = (q, q̇) at SS start on the gait's cycle: q_iSS and q*(α_iSS) α̇_iSS.
Eigen::VectorXd walkingCycleState(const GaitMotion<double>& motion);

// The closed-loop walking map on x = (q, q̇) ∈ R¹⁰ at SS start; throws std::runtime_error
// (with the outcome) when the step is not completed.
StepMap walkingStepMap(const GaitEvaluation<double>& evaluation, const Model& controller,
                       const Model& plant, const WalkRequest& base,
                       const TouchdownMap& touchdown = impulseFreeTouchdown());

}  // namespace gaitopt
