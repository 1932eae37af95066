#pragma once
// Ramp-in from standing still to a cyclic gait and ramp-out back to standing (`gaitopt export
// --ramp`). Every phase is the robot's dynamics along a path, not a kinematic blend:
// - the standing start: a DS from rest (both feet down) to the first SS start, on a path of
//   its own (δ1, δ2 cubic in α from a free rest configuration Δα behind the gait's DS end,
//   α(t) the cubic (3.27) from rest): the gait's DS range is far too short to accelerate
//   within the friction cone;
// - ramp-in steps: the gait's SS path (3.2) from a slower start rate (zero dynamics
//   (3.14)–(3.16), the unactuated ankle leaves no other choice), then the gait's DS path from
//   the touchdown rate to the next start rate (α(t) cubic, its duration scanned);
// - cyclic steps: the gait itself;
// - ramp-out steps: a non-cyclic step each — the SS keeps its start (continuous with the
//   previous DS) but its interior point, touchdown configuration and slopes are free, then
//   the DS to the next (slower) start rate, or, for the last, a DS to rest on a path of its
//   own ahead of the touchdown;
// the free quantities found by a derivative-free search (nlopt SBPLX) on the per-sample
// level-5 check (sampleConstraintMaxima), which the caller repeats at the export rate.
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
// before touchdown, (3.44)) at its start rate, or when no design of a standing start or
// ramp-out step holds the constraints (naming the one that stays violated). `cyclic` is the
// evaluation of `p`.
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
// On a gait's own positive level (a dip between nodes): its estimate from samples is only
// that close, the dips being sharp (the 0.8 m/s optimum exceeds its DS torque envelope by
// 0.06413 N·m at the worst 10 kHz sample, 0.06461 N·m at 1 MHz).
constexpr double kRampRelativeTolerance = 1e-2;
std::vector<ConstraintMaximum> gaitBaseline(const GaitEvaluator& evaluator,
                                            const std::shared_ptr<const GaitEvaluation<double>>& gait);

// The maxima exceeding max(0, baseline) (1 + kRampRelativeTolerance) + kRampTolerance.
std::vector<ConstraintMaximum> violations(const std::vector<ConstraintMaximum>& maxima,
                                          const std::vector<ConstraintMaximum>& baseline);

}  // namespace gaitopt
