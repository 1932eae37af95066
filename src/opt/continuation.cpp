#include "gaitopt/opt/continuation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "gaitopt/gait/constraint_summary.hpp"
#include "gaitopt/opt/initial_guess.hpp"
#include "gaitopt/opt/result_order.hpp"

namespace gaitopt {
namespace {

// Full-stage restarts of an attempt in the walk (the configured number when it resumes, and in
// the retries): most walk attempts that end optimal on configs/default.yaml do so without a
// restart, and one that does not is resumed from its last point (resumeWalkAttempt).
constexpr int kWalkRestarts = 1;

bool optimalPoint(const SweepPoint& p) { return p.attempts > 0 && isOptimal(p.result); }

// The serialised progress reporting shared by the chains.
struct ProgressSink {
  ProgressSink(const ProgressFn& f, int n)
      : fn(&f), t0(std::chrono::steady_clock::now()), total(n) {}
  const ProgressFn* fn;
  std::chrono::steady_clock::time_point t0;
  int total;
  int done = 0;
  std::mutex mutex;

  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  void point(const SweepPoint& p) {
    std::lock_guard<std::mutex> lock(mutex);
    ++done;
    if (*fn) (*fn)(SweepProgress{false, p, done, total, elapsed()});
  }
};

struct FreeStart {
  bool optimal = false;
  bool has_speed = false;
  double speed = 0.0;
  GaitParameters parameters;
};

// One chain over the sorted speeds of a chunk.
class Chain {
 public:
  Chain(const GaitEvaluator& ev, const OptimizationRequest& base, const FreeStart& free,
        const std::vector<double>& speeds, ProgressSink& sink)
      : ev_(ev), base_(base), free_(free), speeds_(speeds), sink_(sink), points_(speeds.size()) {
    for (std::size_t i = 0; i < speeds.size(); ++i) points_[i].speed = speeds[i];
  }

  std::vector<SweepPoint> run() {
    const int n = static_cast<int>(speeds_.size());
    if (n == 0) return {};
    const int s = startIndex();
    std::vector<int> order{s};
    for (int i = s + 1; i < n; ++i) order.push_back(i);
    for (int i = s - 1; i >= 0; --i) order.push_back(i);

    // Walk: the start from the free-speed optimum, then outward from the last optimum.
    if (free_.optimal)
      attempt(s, free_.parameters, free_.speed, false);
    else
      attempt(s, defaultGuess(s), kNaN, false);
    if (optimalPoint(points_[s])) sink_.point(points_[s]);
    for (int dir : {+1, -1}) {
      int anchor = optimalPoint(points_[s]) ? s : -1;
      for (int i = s + dir; i >= 0 && i < n; i += dir) {
        if (anchor >= 0)
          attempt(i, points_[anchor].result.parameters, speeds_[anchor], true);
        else if (free_.optimal)
          attempt(i, free_.parameters, free_.speed, false);
        else
          attempt(i, defaultGuess(i), kNaN, false);
        if (optimalPoint(points_[i])) {
          anchor = i;
          sink_.point(points_[i]);
        }
      }
    }

    walking_ = false;
    // Unmet speeds, in walk order: the walk's attempt resumed with the configured restarts;
    // then the elastic problem from the kept attempt; a
    // certificate ends the speed's attempts (measured on configs/default.yaml: 1.05 m/s
    // certified after its walk's attempt, its retry of 650 iterations saved). When its point
    // meets the one verdict, an attempt from there (measured: 0.85 m/s, whose attempts ended
    // 8.9e-3 scaled over the DS torque envelope between the nodes, ends from it on a step
    // meeting the verdict, 19641.5, where the solver does not certify an optimum). Otherwise
    // retries from the nearest optimum beyond the speed and from the default initial guess,
    // and the elastic problem again from the attempt then kept. (An attempt from an elastic
    // point whose rows hold but not the verdict measured a lottery: once optimal, more often
    // not, and at 0.75 m/s a worse local optimum than the retries'.)
    for (int i : order) {
      if (optimalPoint(points_[i])) continue;
      resumeWalkAttempt(i);
      if (optimalPoint(points_[i])) {
        sink_.point(points_[i]);
        continue;
      }
      certify(i);
      if (!certified(i) && points_[i].certificate && points_[i].certificate->feasible)
        attempt(i, points_[i].certificate->x, kNaN, false);
      if (!certified(i) && !optimalPoint(points_[i])) {
        const int beyond = nearestOptimumBeyond(i, s);
        if (beyond >= 0) attempt(i, points_[beyond].result.parameters, speeds_[beyond], true);
        if (!optimalPoint(points_[i]) && !tried_default_[i])
          attempt(i, defaultGuess(i), kNaN, false);
        if (!optimalPoint(points_[i])) certify(i);
      }
      sink_.point(points_[i]);
    }
    return points_;
  }

 private:
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  int startIndex() const {
    const int n = static_cast<int>(speeds_.size());
    if (!free_.has_speed) return (n - 1) / 2;
    int best = 0;
    for (int i = 1; i < n; ++i)
      if (std::abs(speeds_[i] - free_.speed) < std::abs(speeds_[best] - free_.speed)) best = i;
    return best;
  }

  // Nearest optimal speed on the far side of i from the start s (either side for s itself,
  // the closer in speed, the lower on ties); −1 if none.
  int nearestOptimumBeyond(int i, int s) const {
    const int n = static_cast<int>(speeds_.size());
    int up = -1, down = -1;
    if (i >= s)
      for (int j = i + 1; j < n && up < 0; ++j)
        if (optimalPoint(points_[j])) up = j;
    if (i <= s)
      for (int j = i - 1; j >= 0 && down < 0; --j)
        if (optimalPoint(points_[j])) down = j;
    if (up < 0) return down;
    if (down < 0) return up;
    return speeds_[up] - speeds_[i] < speeds_[i] - speeds_[down] ? up : down;
  }

  bool certified(int i) const {
    return points_[i].certificate && points_[i].certificate->infeasible();
  }

  // The elastic problem from speed i's kept attempt (once per kept attempt).
  void certify(int i) {
    SweepPoint& p = points_[i];
    if (!p.result.evaluation.motion_computed ||
        (p.certificate && certified_from_[i] == p.result.parameters))
      return;
    certified_from_[i] = p.result.parameters;
    InfeasibilityCertificate c = minimiseViolation(ev_, p.result.parameters, speeds_[i]);
    p.total_iterations += c.iterations;
    p.total_wall_time_s += c.wall_time_s;
    p.certificate = std::move(c);
  }

  // The walk's attempt at speed i, which ended without an optimum, continued from its last
  // point with the configured restarts (the walk allows kWalkRestarts). Measured over seven
  // speed grids of configs/default.yaml: 67 speeds optimal instead of 64 (0.85 m/s of the
  // 10-speed library among them), for 6 % more time.
  void resumeWalkAttempt(int i) {
    const SweepPoint& p = points_[i];
    if (!p.result.evaluation.motion_computed) return;
    const GaitParameters start = p.result.last_parameters;  // `attempt` replaces p.result
    attempt(i, start, p.from_speed, p.warm_started);
  }

  GaitParameters defaultGuess(int i) {
    tried_default_[i] = true;
    return defaultInitialGuess(ev_.model(), speeds_[i]);
  }

  void attempt(int i, const GaitParameters& start, double from_speed, bool warm) {
    OptimizationRequest req = base_;
    req.speed = speeds_[i];
    req.initial = start;
    if (walking_) req.solver.max_restarts = std::min(req.solver.max_restarts, kWalkRestarts);
    OptimizationResult r = optimizeGait(ev_, req, nullptr);
    SweepPoint& p = points_[i];
    ++p.attempts;
    p.total_iterations += r.iterations;
    p.total_wall_time_s += r.wall_time_s;
    // Attempts are made only while the speed has no optimum, so the kept attempt is the
    // first optimal one, else the first meeting the verdict (a solver stop on a feasible
    // step, e.g. from the elastic problem's point), else the one unmet at the highest level,
    // the least violating there (the earlier on ties).
    if (p.attempts == 1 ||
        betterResult(r, p.result, base_.criterion, UnmetOrder::LevelThenViolation)) {
      if (isOptimal(r)) p.certificate.reset();  // an optimum needs no evidence of infeasibility
      p.result = std::move(r);
      p.warm_started = warm;
      p.from_speed = from_speed;
    }
  }

  const GaitEvaluator& ev_;
  const OptimizationRequest& base_;
  const FreeStart& free_;
  const std::vector<double>& speeds_;
  ProgressSink& sink_;
  std::vector<SweepPoint> points_;
  std::vector<bool> tried_default_ = std::vector<bool>(speeds_.size(), false);
  bool walking_ = true;
  // Per speed: the kept attempt the last elastic problem started from.
  std::vector<GaitParameters> certified_from_ = std::vector<GaitParameters>(speeds_.size());
};

}  // namespace

std::string speedText(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::vector<std::vector<double>> splitContiguous(const std::vector<double>& sorted, int count) {
  const int n = static_cast<int>(sorted.size());
  if (count < 1 || count > n)
    throw std::invalid_argument("cannot split " + std::to_string(n) + " speed(s) into " +
                                std::to_string(count) + " chunk(s): need 1 <= chunks <= speeds");
  std::vector<std::vector<double>> chunks;
  for (int k = 0; k < count; ++k) {
    // Floor boundaries: the earlier chunks are the smaller ones.
    const int begin = static_cast<int>(static_cast<long long>(k) * n / count);
    const int end = static_cast<int>(static_cast<long long>(k + 1) * n / count);
    chunks.emplace_back(sorted.begin() + begin, sorted.begin() + end);
  }
  return chunks;
}

std::vector<double> sortedSpeeds(const std::vector<double>& speeds) {
  if (speeds.empty()) throw std::invalid_argument("no speeds to sweep");
  std::vector<double> s = speeds;
  for (double v : s)
    if (!std::isfinite(v) || v <= 0.0)
      throw std::invalid_argument("sweep speed " + speedText(v) + " is not > 0 m/s");
  std::sort(s.begin(), s.end());
  for (std::size_t i = 1; i < s.size(); ++i)
    if (s[i] - s[i - 1] <= kSweepSpeedTolerance)
      throw std::invalid_argument("sweep speed " + speedText(s[i]) + " m/s appears twice");
  return s;
}

std::vector<double> sweepRunSpeeds(const std::vector<double>& speeds,
                                   const SweepSettings& settings) {
  std::vector<double> s = sortedSpeeds(speeds);
  if (settings.jobs < 1) throw std::invalid_argument("jobs must be >= 1");
  if (!settings.sharded) return s;
  if (settings.shard.count < 1 || settings.shard.index < 0 ||
      settings.shard.index >= settings.shard.count)
    throw std::invalid_argument("shard " + std::to_string(settings.shard.index) + "/" +
                                std::to_string(settings.shard.count) + ": expected 0 <= i < n");
  if (settings.shard.count > static_cast<int>(s.size()))
    throw std::invalid_argument("shard count " + std::to_string(settings.shard.count) +
                                " exceeds the number of speeds (" + std::to_string(s.size()) + ")");
  return splitContiguous(s, settings.shard.count)[settings.shard.index];
}

std::vector<SweepPoint> sweepSpeeds(const GaitEvaluator& ev, const OptimizationRequest& base,
                                    const std::vector<double>& speeds,
                                    const SweepSettings& settings, const ProgressFn& progress) {
  const std::vector<double> run = sweepRunSpeeds(speeds, settings);
  ProgressSink sink(progress, static_cast<int>(run.size()));
  // A speed without an optimum gets the elastic problem and retries, not Ipopt after SLSQP
  // converged (measured: 1.0 m/s of 0.2:1.0:0.1 on configs/default.yaml, 10.5 s to the same
  // certificate that the elastic problem gives in 0.2 s).
  OptimizationRequest sweep_base = base;
  sweep_base.solver.ipopt_after_convergence = false;

  // (a) the free-speed optimum, once.
  OptimizationRequest free_request = sweep_base;
  free_request.speed.reset();
  SweepPoint free_point;
  free_point.result = optimizeGait(ev, free_request, nullptr);
  free_point.attempts = 1;
  free_point.total_iterations = free_point.result.iterations;
  free_point.total_wall_time_s = free_point.result.wall_time_s;
  free_point.from_speed = std::numeric_limits<double>::quiet_NaN();
  FreeStart free;
  free.optimal = isOptimal(free_point.result);
  free.has_speed = zeroDynamicsComputed(ev, free_point.result.evaluation) &&
                   std::isfinite(free_point.result.evaluation.speed);
  free.speed = free.has_speed ? free_point.result.evaluation.speed : 0.0;
  free.parameters = free_point.result.parameters;
  free_point.speed = free.has_speed ? free.speed : std::numeric_limits<double>::quiet_NaN();
  if (progress) progress(SweepProgress{true, free_point, 0, sink.total, sink.elapsed()});

  const int jobs = std::min(settings.jobs, static_cast<int>(run.size()));
  const std::vector<std::vector<double>> chunks = splitContiguous(run, jobs);
  std::vector<std::vector<SweepPoint>> results(chunks.size());
  const bool concurrent = jobs > 1 && base.solver.backend != Backend::Ipopt;
  if (jobs > 1 && !concurrent && settings.warnings)
    *settings.warnings << "warning: speed sweep: backend ipopt is not known to be thread-safe "
                          "(sequential MUMPS): the "
                       << jobs << " chains run one after the other\n";
  if (concurrent) {
    std::vector<std::exception_ptr> errors(chunks.size());
    std::vector<std::thread> threads;
    for (std::size_t c = 0; c < chunks.size(); ++c)
      threads.emplace_back([&, c]() {
        try {
          results[c] = Chain(ev, sweep_base, free, chunks[c], sink).run();
        } catch (...) {
          errors[c] = std::current_exception();
        }
      });
    for (std::thread& t : threads) t.join();
    for (const std::exception_ptr& e : errors)
      if (e) std::rethrow_exception(e);
  } else {
    for (std::size_t c = 0; c < chunks.size(); ++c)
      results[c] = Chain(ev, sweep_base, free, chunks[c], sink).run();
  }
  std::vector<SweepPoint> out;
  for (std::vector<SweepPoint>& r : results)
    for (SweepPoint& p : r) out.push_back(std::move(p));
  return out;
}

}  // namespace gaitopt
