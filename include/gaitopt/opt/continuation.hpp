#pragma once
// Speed sweeps by continuation (§3.6 of the thesis: the first optimum of a sweep comes from a
// free-speed optimisation, every other speed is warm-started from the optimum at a nearby
// speed) and the split of a speed list into contiguous chunks (--jobs, --shard). sweep.csv and
// the speed-range syntax of `gaitopt sweep`: io/sweep_file.hpp.
//
// A chain over a sorted list of speeds: (a) the free-speed optimum (computed once per call),
// (b) the listed speed closest to its speed, started from it, (c) outward in both directions,
// each speed started from the last optimal speed on its side (the free-speed optimum while there
// is none), (d) afterwards each speed that is not optimal gets the elastic problem
// (opt/infeasibility_certificate.hpp) from its kept attempt: a certificate (s* > 0) ends its
// attempts, the speed shown infeasible with its blocking rows; a point of the elastic problem
// that meets the feasibility verdict is the start of one more attempt; while there is no
// optimum the speed is retried once from the nearest optimum beyond it (further from the
// chain's start), when there is one, then once from defaultInitialGuess, and the elastic
// problem runs again from the attempt then kept. With jobs > 1 the list is cut into `jobs`
// contiguous chunks, each an independent chain (started at its speed closest to the
// free-speed optimum) on its own thread; each chunk's results are exactly those of a
// one-chain run on that chunk alone (e.g. a shard).
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "gaitopt/opt/infeasibility_certificate.hpp"
#include "gaitopt/opt/optimizer.hpp"

namespace gaitopt {

// Limits of a sweep: the number of speeds, and how close two speeds may be [m/s].
constexpr int kMaxSweepSpeeds = 10000;
constexpr double kSweepSpeedTolerance = 1e-9;

// `v` with six significant digits, as a user would write it ("0.2", not 0.20000000000000001).
std::string speedText(double v);

// Chunk `index` (0-based) of `count`.
struct Shard {
  int index = 0;
  int count = 1;
};

// `count` contiguous chunks of `sorted`, sizes differing by at most one (the later chunks take
// the extra elements); throws std::invalid_argument if count < 1 or count > sorted.size().
std::vector<std::vector<double>> splitContiguous(const std::vector<double>& sorted, int count);

// The sorted speeds with the checks of sweepSpeeds (non-empty, finite, > 0, no duplicates);
// throws std::invalid_argument.
std::vector<double> sortedSpeeds(const std::vector<double>& speeds);

struct SweepPoint {
  double speed = 0.0;         // the requested speed [m/s]
  OptimizationResult result;  // the attempt kept: the first optimal one, else the first meeting
                              // the verdict, else the one unmet at the highest level, the least
                              // violating there
  bool warm_started = false;  // that attempt started from another listed speed's optimum
  double from_speed = 0.0;    // speed of the optimum it started from: a listed speed, the free
                              // speed (chain start), NaN when it started from defaultInitialGuess
                              // or from the elastic problem's step
  int attempts = 0;           // optimisations run for this speed (1–4)
  int total_iterations = 0;   // over all attempts and the elastic problem
  double total_wall_time_s = 0.0;
  // The last elastic problem, when the speed's attempts ended without an optimum (from the
  // attempt kept at that time).
  std::optional<InfeasibilityCertificate> certificate;
};

struct SweepSettings {
  int jobs = 1;          // independent chains (threads); clamped to the number of speeds
  bool sharded = false;  // keep only chunk shard.index of shard.count (one chain per job)
  Shard shard;
  std::ostream* warnings = nullptr;  // e.g. "ipopt: chains run one after the other"
};

// One progress report: the free-speed start (free_speed true, point.speed = the speed reached,
// done = 0) or a listed speed whose result is final (done = how many are final so far).
// Calls are serialised (never concurrent), but with jobs > 1 they come from worker threads.
struct SweepProgress {
  bool free_speed = false;
  const SweepPoint& point;
  int done = 0;
  int total = 0;
  double elapsed_s = 0.0;  // since sweepSpeeds started
};
using ProgressFn = std::function<void(const SweepProgress&)>;

// The speeds of the run (the shard's chunk when sharded), sorted; throws std::invalid_argument
// for a bad list or shard.
std::vector<double> sweepRunSpeeds(const std::vector<double>& speeds,
                                   const SweepSettings& settings);

// Results in increasing speed order, one per speed of sweepRunSpeeds. `base` gives the
// criterion, the solver settings and the initial guess of the free-speed optimisation; its
// `speed` is ignored. Deterministic for given speeds, settings.jobs and shard. If the backend
// is Ipopt, chains run one after the other even with jobs > 1 (a warning is written), since
// Ipopt with the sequential MUMPS solver is not known to be thread-safe.
std::vector<SweepPoint> sweepSpeeds(const GaitEvaluator& evaluator, const OptimizationRequest& base,
                                    const std::vector<double>& speeds,
                                    const SweepSettings& settings, const ProgressFn& progress = {});

}  // namespace gaitopt
