#pragma once
// The closed-loop walking map (sim/poincare.hpp: x = (q, q̇) at SS start → the next SS start)
// with its Jacobian by the variational equations along the hybrid orbit (§4.3.2): the SS flow
// to the touchdown event α = α_fSS with the saltation projection of the event time, the
// touchdown/exchange map's Jacobian (central differences of the TouchdownMap, exact for the
// linear relabelling (3.22), (3.23)), and the DS flow over T_DS, whose α reference starts at
// the touchdown state (α, α̇) and so depends on it (carried as two constant states), or, with
// the time-optimal DS control, up to the event α = α_fDS; no DS when the touchdown map says the
// rear foot lifts. The vector field is the simulation's own (evaluateClosedLoop). One
// trajectory instead of the 20 of the finite-difference Jacobian. The torque projection
// (math/small_qp.hpp) makes the field non-smooth where a limit becomes active: the Jacobian is
// that of the walking map only when no limit switches on the cycle (the stability command
// reports the saturated samples of the cycle).
#include "gaitopt/sim/poincare.hpp"
#include "gaitopt/sim/variational_flow.hpp"

namespace gaitopt {

struct StepSensitivity {
  Eigen::VectorXd x_next;    // P(x)
  Eigen::MatrixXd jacobian;  // ∂P/∂x
};

// The simulation's closed loop (sim/closed_loop.hpp) for a request.
ClosedLoop walkingClosedLoop(const GaitMotion<double>& motion, const Model& controller,
                             const Model& plant, const WalkRequest& request);

// The closed-loop SS (x = (q, q̇)) ending at the touchdown event (`at_touchdown`) or when α
// falls to alpha_end. `loop` must outlive the phase.
HybridPhase walkingSingleSupport(const ClosedLoop& loop, double alpha_end, bool at_touchdown);

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
