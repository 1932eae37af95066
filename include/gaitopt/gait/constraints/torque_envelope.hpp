#pragma once
// Torque envelope of the motors (3.46), (3.47): |Γ*_j| ≤ Γmax(ω_j) at every joint, Γmax the
// torque–speed envelope of the RS420J motors (model/torque_envelope.hpp).
#include <array>

#include "gaitopt/gait/constraints/group_spec.hpp"
#include "gaitopt/math/types.hpp"
#include "gaitopt/model/model.hpp"
#include "gaitopt/model/torque_envelope.hpp"

namespace gaitopt {

// (3.47): Γmax of the four joints at joint speeds ω; full: the speed-dependent envelope,
// otherwise its stall torque.
template <class S>
Vector4<S> jointTorqueLimits(const TorqueEnvelope& e, const Vector4<S>& omega, bool full) {
  Vector4<S> limit;
  for (int j = 0; j < 4; ++j) limit(j) = torqueLimit(e, omega(j), full);
  return limit;
}

// (3.46): the rows (Γ* ≤ Γmax, −Γ* ≤ Γmax) of one joint.
template <class S> std::array<S, 2> torqueEnvelopeRows(const S& gamma_star, const S& limit) {
  return {gamma_star - limit, -gamma_star - limit};
}

inline double torqueScale(const Model& m) { return m.robot.envelope.torque[0]; }

constexpr const char* kTorqueUnit = "N m";
constexpr ConstraintGroupSpec kTorqueSsSpec{"torque_envelope_ss", 5, "(3.46), (3.47)", kTorqueUnit,
                                            torqueScale, ConstraintPhase::SingleSupport, 8};
constexpr ConstraintGroupSpec kTorqueDsSpec{"torque_envelope_ds", 5, "(3.46), (3.47)", kTorqueUnit,
                                            torqueScale, ConstraintPhase::DoubleSupport, 8};

}  // namespace gaitopt
