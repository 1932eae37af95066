#pragma once
// The closed-loop walking map (sim/poincare.hpp: x = (q, q̇) at SS start → the next SS start)
// with its Jacobian by the variational equations along the hybrid orbit (§4.3.2): the SS flow
// to the touchdown event α = α_fSS with the saltation projection of the event time, the
// touchdown/exchange map's Jacobian (central differences of the TouchdownMap, exact for the
// linear relabelling (3.22), (3.23)), and the DS flow over T_DS, whose α reference starts at
// the touchdown state (α, α̇) and so depends on it (carried as two constant states). One
// trajectory instead of the 20 of the finite-difference Jacobian.
#include "gaitopt/sim/poincare.hpp"
#include "gaitopt/sim/variational_flow.hpp"

namespace gaitopt {

struct StepSensitivity {
  Eigen::VectorXd x_next;    // P(x)
  Eigen::MatrixXd jacobian;  // ∂P/∂x
};

// The closed-loop SS (x = (q, q̇)) ending when α falls to alpha_end.
HybridPhase walkingSingleSupport(const GaitMotion<double>& motion, const Model& controller,
                                 const Model& plant, const WalkRequest& request, double alpha_end);

// Throws std::runtime_error when the touchdown is not reached or cannot be mapped. The plant's
// contact and fall checks are those of walkingStepMap, not repeated here: linearise at a cycle
// that walkingStepMap walks. Without `with_jacobian` only x_next (the same hybrid map, for
// checking the Jacobian by differences).
StepSensitivity walkingStepSensitivity(const GaitEvaluation<double>& evaluation,
                                       const Model& controller, const Model& plant,
                                       const WalkRequest& request, const Eigen::VectorXd& x,
                                       const TouchdownMap& touchdown = impulseFreeTouchdown(),
                                       bool with_jacobian = true);

PoincareLinearisation linearisePoincareBySensitivity(
    const GaitEvaluation<double>& evaluation, const Model& controller, const Model& plant,
    const WalkRequest& request, const Eigen::VectorXd& x,
    const TouchdownMap& touchdown = impulseFreeTouchdown());

}  // namespace gaitopt
