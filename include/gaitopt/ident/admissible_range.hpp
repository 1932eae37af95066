#pragma once
// The values each effect of the library (ident/effects.hpp) can physically have on a given
// robot. A fitted value at or beyond its range is not a cause (ident/diagnose.hpp): it says the
// data carry something the library does not describe, and the candidate that soaks it up best
// is reported as a partial fit with the reason.
#include <string>

#include "gaitopt/ident/effects.hpp"

namespace gaitopt {

// Open interval (lo, hi) of an effect's value, in its convention (added to, or a factor on,
// what the robot file already has), and why.
struct AdmissibleRange {
  double lo = 0.0, hi = 0.0;
  std::string basis;  // e.g. "±0.25 × trunk length 0.625 m"
  bool contains(double value) const { return value > lo && value < hi; }
  bool containsClosed(double value) const { return value >= lo && value <= hi; }
};

// The range of `e`'s kind on `e`'s joint of `robot` (the robot file the data are compared with):
// friction stays ≥ 0 in total, the rotor-inertia factor > 0, sensor offsets and gains within a
// few % of the torque envelope, the trunk CoM on the trunk, a payload against the total mass,
// the rocker radius and foot offset against the leg length. The whole real line for `inertial`
// (its fit is physically consistent by construction).
AdmissibleRange admissibleRange(const Effect& e, const RobotParams& robot);

// How far beyond the admissible range `gaitopt synth` generates a hidden effect: diagnose's tests
// need truths it must refuse as causes, not physically absurd ones.
constexpr double kSynthesisRangeMultiple = 10.0;

// The closed range of values `synth` accepts for `e` on `robot`: the admissible range stretched
// kSynthesisRangeMultiple times about the neutral value (0, or 1 for a factor), keeping the
// physical laws among its bounds — total friction, dead band and rocker radius >= 0, factors
// >= 0 (> 0 by the spec), the robot's total mass >= 0. The whole real line for `inertial`.
AdmissibleRange synthesisRange(const Effect& e, const RobotParams& robot);

// "trunk_com -0.46 m is outside its physical range (-0.156, 0.156) m: ±0.25 × trunk length …".
std::string inadmissibleReason(const Effect& e, const AdmissibleRange& range);

// The reason the first of `effects` outside its range on `robot` is, or "" when all are inside.
std::string firstInadmissible(const std::vector<Effect>& effects, const RobotParams& robot);

}  // namespace gaitopt
