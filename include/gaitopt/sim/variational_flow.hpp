#pragma once
// One phase of a hybrid system with its sensitivity: ẋ = f(t, x) integrated together with the
// variational equation Ṡ = fₓ(t, x) S (S = ∂x(t)/∂x₀ · S₀) in one CVODE system, so the
// sensitivities are under the same error control as the state. fₓ s is a central directional
// difference of f (as CVODES's internal difference-quotient sensitivity right-hand side), so
// any vector field can be used as it is. A phase ends at a falling zero of the event function
// g(x) (or at t_end); there S is projected onto the event surface, S ← (I − f gₓ/(gₓ f)) S,
// the derivative of the state at the (state-dependent) event time. A reset map after the event
// is the caller's: S ← DΔ S.
#include <Eigen/Core>
#include <functional>

#include "gaitopt/sim/cvode_integrator.hpp"

namespace gaitopt {

struct HybridPhase {
  CvodeIntegrator::Rhs field;
  std::function<double(const Eigen::VectorXd& x)> event;  // null: the phase ends at t_end
};

struct SensitiveState {
  double t = 0.0;
  Eigen::VectorXd x;
  Eigen::MatrixXd S;  // ∂x/∂(the map's argument), x.size() rows
};

struct PhaseEnd {
  SensitiveState state;
  bool event = false;  // the event was reached (else t_end)
};

PhaseEnd flowWithSensitivity(const HybridPhase& phase, const SensitiveState& start, double t_end,
                             const CvodeTolerances& tol);

// Central-difference Jacobian of a map (the reset maps, the event gradient), steps h.
Eigen::MatrixXd centralJacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& F,
                                const Eigen::VectorXd& x, double h);

}  // namespace gaitopt
