#include "gaitopt/gait/constraints.hpp"

#include "gaitopt/gait/constraints/boundary_order.hpp"
#include "gaitopt/gait/constraints/clearance.hpp"
#include "gaitopt/gait/constraints/contact.hpp"
#include "gaitopt/gait/constraints/ds_monotone.hpp"
#include "gaitopt/gait/constraints/impact_landing.hpp"
#include "gaitopt/gait/constraints/joint_limits.hpp"
#include "gaitopt/gait/constraints/reach.hpp"
#include "gaitopt/gait/constraints/torque_envelope.hpp"
#include "gaitopt/gait/constraints/touchdown_speed.hpp"
#include "gaitopt/gait/constraints/zero_dynamics.hpp"
#include "gaitopt/gait/impact_landing.hpp"

namespace gaitopt {
namespace {

// In ConstraintGroupId order.
const ConstraintGroupSpec* const kRegistry[] = {
    &kReachMaxIdsSpec, &kReachMinIdsSpec, &kReachMaxFdsSpec, &kReachMinFdsSpec,
    &kReachMaxIntSpec, &kReachMinIntSpec,
    &kAlphaOrderDsSpec, &kAlphaOrderSsSpec, &kTibiaFrontSpec, &kTibiaRearSpec,
    &kFPositiveSpec,
    &kAlphadotNegativeSpec, &kNoFallBackSpec,
    &kKappaPositiveSpec, &kDsReachMaxSpec, &kDsReachMinSpec,
    &kTorqueSsSpec, &kJointLimitsSsSpec, &kFrictionConeSsSpec, &kNormalForceSsSpec,
    &kClearanceSpec,
    &kTorqueDsSpec, &kJointLimitsDsSpec, &kFrictionConeDsSpec, &kNormalForceDsSpec, &kDsMonotoneSpec,
    &kImpactArrivalSpec, &kImpactConsistencySpec, &kImpactRateRatioSpec, &kImpactOrbitSpec,
    &kTouchdownSpeedSpec,
};
static_assert(sizeof(kRegistry) / sizeof(kRegistry[0]) == kNumConstraintGroups,
              "one registry entry per ConstraintGroupId");

}  // namespace

double constraintGroupScale(int group, const Model& m) { return kRegistry[group]->scale(m); }

ConstraintLayout::ConstraintLayout(const GaitOptions& o) {
  const int ss = o.ss_nodes + 1;
  const Parameterisation& par = o.parameterisation;
  const bool impact = par.landsWithImpact(), single = !par.hasDoubleSupport();
  // Without DS the SS starts at the impact configuration: no DS groups, and the (α_fDS, …)
  // configuration, equal to (α_iDS, …), is not checked twice.
  const int ds = single ? 0 : o.ds_nodes + 1;
  const auto present = [&](ConstraintPresence p) {
    switch (p) {
      case ConstraintPresence::WithDoubleSupport: return single ? 0 : 1;
      case ConstraintPresence::WithoutDoubleSupport: return single ? 1 : 0;
      case ConstraintPresence::WithImpact: return impact ? 1 : 0;
      case ConstraintPresence::WithoutImpact: return impact ? 0 : 1;
      case ConstraintPresence::ImpactSlacks:
        return impact ? landingImpactSlackCount(par.landing) : 0;
      case ConstraintPresence::WithTouchdownSpeed:
        return impact && o.touchdown_speed_min > 0.0 ? 1 : 0;
      default: return 1;
    }
  };
  for (int id = 0; id < kNumConstraintGroups; ++id) {
    const ConstraintGroupSpec& s = *kRegistry[id];
    const int points = s.phase == ConstraintPhase::SingleSupport ? ss - 2 * s.first_point
                       : s.phase == ConstraintPhase::DoubleSupport ? ds
                                                                   : 1;
    const int count = s.phase == ConstraintPhase::None ? present(s.presence) : s.per_point * points;
    const char* unit = single && s.unit_without_ds ? s.unit_without_ds : s.unit;
    groups_.push_back({s.name, s.level, s.equation, size_, count, unit, s.phase,
                       points > 0 ? count / points : 0, s.first_point});
    size_ += count;
    entry_level_.insert(entry_level_.end(), count, s.level);
  }
}

int ConstraintLayout::levelOf(int entry) const { return entry_level_[entry]; }

int ConstraintLayout::dsMotionSize() const {
  return groups_[kDsMonotone].offset + groups_[kDsMonotone].count - dsMotionOffset();
}

}  // namespace gaitopt
