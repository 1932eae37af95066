#pragma once
// The level-5 entries of a step at one phase sample, from the rows of the registry's families
// (gait/constraints/), each passed to put(group, index, value): to the layout at a grid node,
// or to a DS piece's samples (GaitEvaluation::ds_piece_g).
#include <array>

#include "gaitopt/gait/constraints/clearance.hpp"
#include "gaitopt/gait/constraints/contact.hpp"
#include "gaitopt/gait/constraints/ds_monotone.hpp"
#include "gaitopt/gait/constraints/joint_limits.hpp"
#include "gaitopt/gait/constraints/torque_envelope.hpp"
#include "gaitopt/gait/evaluation_context.hpp"
#include "gaitopt/gait/phase_sample.hpp"

namespace gaitopt::detail {

// The torque envelope (3.46), (3.47) and joint limits (3.42) of one sample at node k, joint j's
// two rows at 8 k + 2 j.
template <class S, class Put>
void phaseConstraintValues(const EvalContext<S>& c, int torque_group, int limits_group, int k,
                           const PhaseSample<S>& s, Put&& put) {
  const RobotParams& r = c.model.robot;
  const Vector4<S> limit = jointTorqueLimits(r.envelope, s.omega, c.options.full_torque_envelope);
  const std::array<S, 4> angles = jointLimitAngles(s.q);
  for (int j = 0; j < 4; ++j) {
    const std::array<S, 2> torque = torqueEnvelopeRows(S(s.gamma_star(j)), S(limit(j)));
    const std::array<S, 2> range =
        jointLimitRows(r.limits, j, angles[j], c.options.joint_limit_margin);
    for (int i = 0; i < 2; ++i) {
      put(torque_group, 8 * k + 2 * j + i, torque[i]);
      put(limits_group, 8 * k + 2 * j + i, range[i]);
    }
  }
}

// The friction cone and normal force (3.48) of foot `foot` of `feet` at node k.
template <class S, class Put>
void contactConstraintValues(const EvalContext<S>& c, int cone_group, int normal_group, int foot,
                             int feet, int k, const Vector2<S>& R, Put&& put) {
  const std::array<S, 2> cone = frictionConeRows(R, c.options.friction_coefficient);
  put(cone_group, 2 * (feet * k + foot), cone[0]);
  put(cone_group, 2 * (feet * k + foot) + 1, cone[1]);
  put(normal_group, feet * k + foot, normalForceRow(R, c.options.min_normal_force));
}

// The SS level-5 entries (3.42), (3.46)–(3.49) of one sample at SS node k of n.
template <class S, class Put>
void ssConstraintValues(const EvalContext<S>& c, int k, int n, const PhaseSample<S>& s, Put&& put) {
  phaseConstraintValues(c, kTorqueSS, kJointLimitsSS, k, s, put);
  contactConstraintValues(c, kFrictionConeSS, kNormalForceSS, 0, 1, k, s.R1, put);
  if (k == 0 || k == n - 1) return;  // (3.49) on the open interval (gap #16)
  const S x = s.foot2(0) / c.out.motion.d;
  put(kClearance, k - 1,
      clearanceRow(S(s.foot2(1)), clearanceProfile(x, c.options.clearance_height)));
}

// The DS level-5 entries (3.42), (3.43), (3.46)–(3.48) of one sample at DS node k.
template <class S, class Put>
void dsConstraintValues(const EvalContext<S>& c, int k, const PhaseSample<S>& s, Put&& put) {
  phaseConstraintValues(c, kTorqueDS, kJointLimitsDS, k, s, put);
  contactConstraintValues(c, kFrictionConeDS, kNormalForceDS, 0, 2, k, s.R1, put);
  contactConstraintValues(c, kFrictionConeDS, kNormalForceDS, 1, 2, k, s.R2, put);
  put(kDsMonotone, k, dsMonotoneRow(S(s.qd(0)), c.options.ds_alphadot_max));
}

// A writer of entries into the layout, all in state st.
template <class S> auto layoutWriter(EvalContext<S>& c, ConstraintState st) {
  return [&c, st](int group, int index, const S& value) { c.set(group, index, value, st); };
}

}  // namespace gaitopt::detail
