#pragma once
// The named constraints of a walking step (§3.2.3), their hierarchy level (Fig. 3.2 as
// reconstructed in digest §3.8) and their place in the flat constraint vector. Every value is
// written g ≤ 0 when satisfied. Phase-wise (semi-infinite) constraints have one entry per node
// of the phase's Chebyshev grid, so the optimiser sees a smooth, fixed-size set. A group a
// gait family does not have (the DS of an impact followed by single support, the impact of
// the thesis' landing) has count 0.
#include <string>
#include <vector>

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
  kNumConstraintGroups
};

constexpr int kNumLevels = 6;

// The one feasibility tolerance of gaitopt: an entry counts as violated when
// g > kFeasibilityTolerance × (its group's typical magnitude, ConstraintGroup::scale), the
// speed when |speed − target| > kFeasibilityTolerance × 1 m/s. The evaluator's hierarchy, the
// optimiser's status, summary.json and `gaitopt evaluate` all use it (gait/feasibility.hpp).
constexpr double kFeasibilityTolerance = 1e-6;

enum class ConstraintPhase : unsigned char { None, SingleSupport, DoubleSupport };

struct ConstraintGroup {
  std::string name;
  int level;
  std::string equation;  // thesis reference
  int offset;            // first entry in the flat vector
  int count;
  double scale;          // typical magnitude of the values (the optimiser sees g / scale)
  ConstraintPhase phase;  // phase-wise (semi-infinite) groups: one block of entries per point
  int per_point;          // entries per grid point (phase-wise groups)
  int first_point;        // first grid point carrying the group (1 for the clearance)
};

// State of one entry after an evaluation.
enum class ConstraintState : unsigned char {
  NotComputed,  // a lower level failed and no saturation/extension reaches it
  Extended,     // computed through a saturation (3.54)–(3.56) or extension (3.53) only
  Defined,      // all lower levels hold
};

class ConstraintLayout {
 public:
  // Phase-wise groups have one block per Chebyshev node of the phase, then one per extra point
  // of options.ss_extra_points / ds_extra_points.
  ConstraintLayout(const GaitOptions& options, const Model& model);
  const std::vector<ConstraintGroup>& groups() const { return groups_; }
  const ConstraintGroup& operator[](int id) const { return groups_[id]; }
  int size() const { return size_; }
  int levelOf(int entry) const;
  bool has(int group) const { return groups_[group].count > 0; }
  int groupOf(int entry) const { return entry_group_[entry]; }
  double scaleOf(int entry) const { return groups_[entry_group_[entry]].scale; }
  // Whether the value g of an entry exceeds the feasibility tolerance.
  bool violates(int entry, double g) const {
    return g > kFeasibilityTolerance * scaleOf(entry);
  }

 private:
  std::vector<ConstraintGroup> groups_;
  std::vector<int> entry_level_, entry_group_;
  int size_ = 0;
};

}  // namespace gaitopt
