#pragma once
// Forward dynamics of the pinned single-support model (1.32) with R2 = 0, and a fixed-step
// integrator for simulation and tests.
#include <functional>

#include "gaitopt/model/model.hpp"
#include "gaitopt/model/joint_friction.hpp"

namespace gaitopt {

// q̈ = A⁻¹ (D_Γ Γ − C − G), Γ = Γ* − friction(ω).
Vec5 forwardDynamicsSS(const Model& model, const Vec5& q, const Vec5& qd, const Vec4& gamma_star,
                       SignMode mode);

// Mechanical energy ½ q̇ᵀ A q̇ + M g z_G of the pinned robot (rotors included).
double pinnedEnergy(const Model& model, const Vec5& q, const Vec5& qd);

struct PinnedState {
  Vec5 q, qd;
};
using TorqueLaw = std::function<Vec4(double t, const PinnedState&)>;

// Classical fourth-order Runge–Kutta with fixed step: deterministic and accurate enough for the
// smooth single-support dynamics over a few seconds (error O(dt⁴)).
PinnedState simulateSS(const Model& model, const PinnedState& x0, const TorqueLaw& torque,
                       double duration, double dt, SignMode mode);

}  // namespace gaitopt
