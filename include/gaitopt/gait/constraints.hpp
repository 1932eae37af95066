#pragma once
// The registry of the named constraints of a walking step (§3.2.3): one table of the groups
// defined by the family headers of gait/constraints/ (their row values, hierarchy level (Fig.
// 3.2 as reconstructed in digest §3.8), equation, unit and scale), and their place in the flat
// constraint vector. Every value is written g ≤ 0 when satisfied. Phase-wise (semi-infinite)
// constraints have one entry per node of the phase's Chebyshev grid, so the optimiser sees a
// smooth, fixed-size set. A group a gait family does not have (the DS of an impact followed by
// single support, the impact of the thesis' landing) has count 0.
#include <string>
#include <vector>

#include "gaitopt/gait/constraints/group_spec.hpp"
#include "gaitopt/gait/options.hpp"

namespace gaitopt {

struct Model;

enum ConstraintGroupId : int {
  kReachMaxIDS, kReachMinIDS, kReachMaxFDS, kReachMinFDS, kReachMaxInt, kReachMinInt,  // level 0
  kAlphaOrderDS, kAlphaOrderSS, kTibiaFront, kTibiaRear,                              // level 1
  kFPositive,                                                                         // level 2
  kAlphadotNegative, kNoFallBack,                                                     // level 3
  kKappaPositive, kDsReachMax, kDsReachMin,                                           // level 4
  kTorqueSS, kJointLimitsSS, kFrictionConeSS, kNormalForceSS, kClearance,             // level 5
  kTorqueDS, kJointLimitsDS, kFrictionConeDS, kNormalForceDS, kDsMonotone,
  // Landing with an impact (gait/impact_landing.hpp): level 1, and level 3 for the orbit.
  kImpactArrival, kImpactConsistency, kImpactRateRatio, kImpactOrbit,
  // Touchdown at a minimum downward foot speed (GaitOptions::touchdown_speed_min): level 5.
  kTouchdownSpeed,
  kNumConstraintGroups
};

constexpr int kNumLevels = 6;

// The one feasibility tolerance of gaitopt: an entry is unmet when its value exceeds
// kFeasibilityTolerance × its group's typical magnitude (constraintGroupScale), the speed when
// |speed − target| > kFeasibilityTolerance m/s. The optimiser's status, summary.json and
// `gaitopt evaluate` share it (gait/feasibility.hpp).
constexpr double kFeasibilityTolerance = 1e-6;

struct ConstraintGroup {
  std::string name;
  int level;
  std::string equation;  // thesis reference
  int offset;            // first entry in the flat vector
  int count;
  std::string unit;      // of the values g, for this gait family
  ConstraintPhase phase = ConstraintPhase::None;
  int per_point = 1;
  int first_point = 0;
};

// Typical magnitude of a constraint group's values (the optimiser sees g / scale, O(1)).
double constraintGroupScale(int group, const Model& model);

// State of one entry after an evaluation.
enum class ConstraintState : unsigned char {
  NotComputed,  // a lower level failed and no saturation/extension reaches it
  Extended,     // computed through a saturation (3.54)–(3.56) or extension (3.53) only
  Defined,      // all lower levels hold
};

class ConstraintLayout {
 public:
  explicit ConstraintLayout(const GaitOptions& options);
  const std::vector<ConstraintGroup>& groups() const { return groups_; }
  const ConstraintGroup& operator[](int id) const { return groups_[id]; }
  int size() const { return size_; }
  int levelOf(int entry) const;
  bool has(int group) const { return groups_[group].count > 0; }
  // The DS level-5 groups torque_envelope_ds … ds_monotone, contiguous in the layout: their
  // first entry and their number of entries (0 without DS).
  int dsMotionOffset() const { return groups_[kTorqueDS].offset; }
  int dsMotionSize() const;

 private:
  std::vector<ConstraintGroup> groups_;
  std::vector<int> entry_level_;
  int size_ = 0;
};

}  // namespace gaitopt
