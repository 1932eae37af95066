#pragma once
// What one named constraint group is, independently of a gait's grids: its name, hierarchy
// level (Fig. 3.2 as reconstructed in digest §3.8), thesis equation, unit and typical magnitude,
// and how many entries it has. Each family header of gait/constraints/ defines the specs of its
// groups next to their row values; gait/constraints.hpp lays them out in one table.
namespace gaitopt {

struct Model;

// Phase-wise (semi-infinite) groups hold one block of per_point entries per node of their
// phase's Chebyshev grid, from node first_point on (the clearance skips both phase ends).
enum class ConstraintPhase : unsigned char { None, SingleSupport, DoubleSupport };

// Entries of a group that is not phase-wise, by the gait family (gait/parameters.hpp).
enum class ConstraintPresence : unsigned char {
  Always,                // one entry
  WithDoubleSupport,     // one entry when the step has a DS
  WithoutDoubleSupport,  // one entry when it has none (an impact followed by single support)
  WithImpact,            // one entry when the step lands with an impact
  WithoutImpact,         // one entry when it lands without
  ImpactSlacks,          // the landing's behaviour slacks (landingImpactSlackCount)
  WithTouchdownSpeed,    // one entry when it lands with an impact at a minimum foot speed
};

struct ConstraintGroupSpec {
  const char* name;
  int level;
  const char* equation;  // thesis reference
  const char* unit;      // of the values g
  double (*scale)(const Model&);  // typical magnitude of the values (the optimiser sees g / scale)
  ConstraintPhase phase = ConstraintPhase::None;
  int per_point = 1;    // entries per phase node
  int first_point = 0;  // phase nodes skipped at each end
  ConstraintPresence presence = ConstraintPresence::Always;  // groups that are not phase-wise
  const char* unit_without_ds = nullptr;  // when a step without DS has another row (else unit)
};

// Scale of the groups measured in radians, rad/s or a ratio.
inline double dimensionlessScale(const Model&) { return 1.0; }

}  // namespace gaitopt
