#include "gaitopt/gait/constraints.hpp"

#include <cmath>

#include "gaitopt/gait/impact_landing.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {
namespace {

ConstraintPhase phaseOf(int id) {
  if (id == kFPositive || id == kNoFallBack || (id >= kTorqueSS && id <= kClearance))
    return ConstraintPhase::SingleSupport;
  if (id == kDsReachMax || id == kDsReachMin || (id >= kTorqueDS && id <= kDsMonotone))
    return ConstraintPhase::DoubleSupport;
  return ConstraintPhase::None;
}

}  // namespace

// Typical magnitude of each constraint group's values (so Ipopt sees O(1) rows).
double constraintGroupScale(int group, const Model& m) {
  const double reach = std::pow(m.robot.l4 + m.robot.l5, 2);
  const double weight = m.total_mass * m.gravity;
  switch (group) {
    case kReachMaxIDS: case kReachMinIDS: case kReachMaxFDS: case kReachMinFDS:
    case kReachMaxInt: case kReachMinInt: case kDsReachMax: case kDsReachMin:
      return reach;
    case kFPositive: return 10.0;
    case kTorqueSS: case kTorqueDS: return m.robot.envelope.torque[0];
    case kFrictionConeSS: case kFrictionConeDS: case kNormalForceSS: case kNormalForceDS:
      return weight;
    case kClearance: return 0.05;
    default: return 1.0;  // angles [rad], angular rates [rad/s], κ
  }
}

ConstraintLayout::ConstraintLayout(const GaitOptions& o) {
  const int ss = o.ss_nodes + 1;
  const Parameterisation& par = o.parameterisation;
  const bool impact = par.landsWithImpact(), single = !par.hasDoubleSupport();
  // Without DS the SS starts at the impact configuration: no DS groups, and the (α_fDS, …)
  // configuration, equal to (α_iDS, …), is not checked twice.
  const int ds = single ? 0 : o.ds_nodes + 1, dsb = single ? 0 : 1;
  const int slacks = impact ? landingImpactSlackCount(par.landing) : 0;
  struct Spec {
    const char* name;
    int level;
    const char* equation;
    int count;
  };
  const Spec specs[kNumConstraintGroups] = {
      {"reach_max_iDS", 0, "(3.36)", 1},
      {"reach_min_iDS", 0, "(3.36)", 1},
      {"reach_max_fDS", 0, "(3.36)", dsb},
      {"reach_min_fDS", 0, "(3.36)", dsb},
      {"reach_max_int", 0, "(3.37)", 1},
      {"reach_min_int", 0, "(3.37)", 1},
      {"alpha_order_DS", 1, "(3.38)", dsb},
      {"alpha_order_fDS_fSS", 1, "(3.38)", 1},
      {"tibia_front", 1, "(3.40)", 1},
      {"tibia_rear", 1, "(3.40)", 1},
      {"f_positive", 2, "(3.45)", ss},
      {"alphadot_iSS_negative", 3, "(3.15)", 1},
      {"no_fall_back", 3, "(3.44), (3.55)", ss},
      {"kappa_positive", 4, "(3.23)", impact ? 0 : 1},
      {"ds_reach_max", 4, "(3.41)", ds},
      {"ds_reach_min", 4, "(3.41)", ds},
      {"torque_envelope_ss", 5, "(3.46), (3.47)", 8 * ss},
      {"joint_limits_ss", 5, "(3.42)", 8 * ss},
      {"friction_cone_ss", 5, "(3.48)", 2 * ss},
      {"normal_force_ss", 5, "(3.48)", ss},
      {"clearance", 5, "(3.49)", ss - 2},
      {"torque_envelope_ds", 5, "(3.46), (3.47)", 8 * ds},
      {"joint_limits_ds", 5, "(3.42)", 8 * ds},
      {"friction_cone_ds", 5, "(3.48)", 4 * ds},
      {"normal_force_ds", 5, "(3.48)", 2 * ds},
      {"ds_monotone", 5, "(3.43)", ds},
      {"impact_arrival", 1, "(2.2)", impact ? 1 : 0},
      {"impact_consistency", 1, "(2.5), (2.9)-(2.12)", slacks},
      {"impact_rate_ratio", 1, "(3.23)", impact ? 1 : 0},
      {"impact_orbit", 3, "(3.14)", single ? 1 : 0},
  };
  for (int id = 0; id < kNumConstraintGroups; ++id) {
    const Spec& s = specs[id];
    const ConstraintPhase phase = phaseOf(id);
    const int points = phase == ConstraintPhase::SingleSupport
                           ? ss - (id == kClearance ? 2 : 0)
                           : phase == ConstraintPhase::DoubleSupport ? ds : 1;
    groups_.push_back({s.name, s.level, s.equation, size_, s.count, phase,
                       points > 0 ? s.count / points : 0, id == kClearance ? 1 : 0});
    size_ += s.count;
    entry_level_.insert(entry_level_.end(), s.count, s.level);
  }
}

int ConstraintLayout::levelOf(int entry) const { return entry_level_[entry]; }

int ConstraintLayout::dsMotionSize() const {
  return groups_[kDsMonotone].offset + groups_[kDsMonotone].count - dsMotionOffset();
}

}  // namespace gaitopt
