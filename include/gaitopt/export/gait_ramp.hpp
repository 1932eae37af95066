#pragma once
// Ramp-in from standing still to a cyclic gait and ramp-out back to standing (`gaitopt export
// --ramp`). Every step keeps the gait's geometric path — the SS virtual constraints δ(α) (3.2)
// and the DS polynomials δ1, δ2(α) (3.3) — and only the time law changes, so the motion is
// the robot's dynamics along that path, not a kinematic blend:
// - SS of step k: the zero dynamics (3.14)–(3.16) from the step's own start rate a_k (the
//   evaluator run with α̇_iSS = a_k); the unactuated stance ankle leaves no other choice.
// - DS after it: the robot is over-actuated there, so α(t) is prescribed from the touchdown
//   rate κ α̇_fSS (3.23) to the next step's a_{k+1} with constant α̈ (the cubic (3.27) over
//   2Δα / (v0 + v1), which cancels its cubic term and keeps α̇ monotone), R2x split as in the
//   gait (3.62). The cyclic steps keep the gait's own DS.
// - The stop is where this construction meets physics: every SS of the path ends at least as
//   fast as the slowest step's touchdown rate, and the DS cannot absorb that within the
//   friction cone before the rear leg runs out of reach on the shipped gaits; the stop is
//   then reported infeasible (InfeasibleRamp), and `stop = false` exports the ramp-in alone.
// - The walk starts at rest in the DS start configuration (both feet down, step length
//   apart), accelerates along the DS to a_1, and ends decelerating along the last DS to rest
//   in the DS end configuration.
// - Start rates: the path sets a floor (the CoM must pass over the stance foot), so the first
//   ramp-in and the last ramp-out SS start at the slowest walkable rate a_slow and the others
//   ramp the SS start kinetic energy linearly between a_slow and the gait's a*.
// Torques and reactions come from the evaluator's own sampling; the caller checks every
// sample against the evaluator's level-5 constraints (sampleConstraintMaxima).
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/trajectory.hpp"

namespace gaitopt {

// One step of a multi-step walk: the motion sampled (SS, then DS to the next step).
struct WalkStepMotion {
  std::shared_ptr<const GaitEvaluation<double>> evaluation;  // shared by identical steps
  bool single_support = true;  // false: the standing start of a ramp (its DS only)
};

struct RampRequest {
  int steps_in = 2;   // SS steps before the cyclic ones (≥ 1), the first at a_slow
  int steps_out = 2;  // SS steps after them (≥ 1), the last at a_slow
  int cyclic_steps = 1;
  bool stop = true;   // false: no ramp-out, the walk ends with the last cyclic step
};

// SS start rates of the steps walked, in order (ramp-in, cyclic, ramp-out): the first ramp-in
// and the last ramp-out step start at a_slow, the others linearly in α̇² towards a*.
std::vector<double> rampStartRates(double a_star, double a_slow, const RampRequest& request);

// The slowest SS start rate of the gait's path that does not fall back before touchdown: the
// evaluator's saturation (3.56), α̇_min − ε.
double slowestStartRate(const GaitEvaluator& evaluator, const GaitParameters& p);

// The steps of the ramped walk: the standing start, then one step per rampStartRates entry,
// the last ending at rest. Throws InfeasibleRamp when a step's SS is undefined (falls back
// before touchdown, (3.44)) at its start rate. `cyclic` is the evaluation of `p`.
std::vector<WalkStepMotion> rampedWalk(const GaitEvaluator& evaluator, const GaitParameters& p,
                                       const GaitEvaluation<double>& cyclic,
                                       const RampRequest& request);

struct InfeasibleRamp : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A sample of a multi-step walk: the trajectory row of its step (frame of its leg 1) and
// where that step is in the walk.
struct PlannedSample {
  double t;         // from the start of the walk [s]
  int step;         // index in the WalkStepMotion list
  double foot1_x;   // world x of the sample's foot 1 [m]
  bool leg1_is_first_stance;  // leg 1 is the physical leg of the first SS
  TrajectoryRow row;
};

// Samples t_i = i / rate over the whole walk; a sample on a phase boundary belongs to the
// phase starting there (the very last to the final DS).
std::vector<PlannedSample> sampleWalk(const GaitEvaluator& evaluator,
                                   const std::vector<WalkStepMotion>& steps, double rate);

// Largest value over the samples of each level-5 constraint of the evaluator (g ≤ 0 holds,
// in the constraint's unit), with the sample where it occurs. The rest samples of a ramp's
// standing start and stop are held to α̇ ≤ 0 instead of the DS monotonicity margin (3.43).
struct ConstraintMaximum {
  std::string name, unit;
  double value = 0.0;
  double t = 0.0;
  int step = 0;
};
std::vector<ConstraintMaximum> sampleConstraintMaxima(const GaitEvaluator& evaluator,
                                                      const std::vector<WalkStepMotion>& steps,
                                                      const std::vector<PlannedSample>& samples);

}  // namespace gaitopt

namespace gaitopt {

// What a ramp is held to: the gait's own worst sample of each constraint at kBaselineRate (the
// evaluator enforces them at its Chebyshev nodes only, so a gait may dip slightly between
// them, e.g. the default gait's swing foot 35 µm under the clearance parabola).
constexpr double kBaselineRate = 10000.0;  // Hz
constexpr double kRampTolerance = 1e-9;    // on g ≤ 0, in the constraint's unit
std::vector<ConstraintMaximum> gaitBaseline(const GaitEvaluator& evaluator,
                                            const std::shared_ptr<const GaitEvaluation<double>>& gait);

// The maxima exceeding max(0, baseline) + kRampTolerance.
std::vector<ConstraintMaximum> violations(const std::vector<ConstraintMaximum>& maxima,
                                          const std::vector<ConstraintMaximum>& baseline);

}  // namespace gaitopt
