#include "gaitopt/opt/start_runs.hpp"

#include <algorithm>
#include <random>

#include "gaitopt/opt/random_start.hpp"
#include "gaitopt/opt/result_order.hpp"

namespace gaitopt {

StartsSummary summarizeStarts(const std::vector<StartRun>& runs, Criterion c) {
  StartsSummary s;
  for (const StartRun& run : runs) {
    if (!isOptimal(run.result)) continue;
    ++s.converged;
    const double v = criterionValue(run.result.evaluation, c);
    s.min = s.min ? std::min(*s.min, v) : v;
    s.max = s.max ? std::max(*s.max, v) : v;
  }
  return s;
}

std::size_t bestStartRun(const std::vector<StartRun>& runs, Criterion c) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < runs.size(); ++i)
    if (betterResult(runs[i].result, runs[best].result, c, UnmetOrder::LevelThenViolation))
      best = i;
  return best;
}

std::vector<StartRun> optimizeFromRandomStarts(const GaitEvaluator& ev,
                                               const OptimizationRequest& request, int count,
                                               std::uint64_t seed, std::ostream* log,
                                               const std::function<void(const StartRun&)>& after_run) {
  std::mt19937_64 rng(seed);
  std::vector<StartRun> runs;
  for (int k = 1; k <= count; ++k) {
    OptimizationRequest req = request;
    req.initial = randomStart(request.initial, rng, ev.options().parameterisation);
    if (log) *log << "--- random start " << k << "/" << count << "\n";
    runs.push_back({k, optimizeGait(ev, req, log)});
    if (after_run) after_run(runs.back());
  }
  return runs;
}

}  // namespace gaitopt
