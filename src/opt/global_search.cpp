#include "gaitopt/opt/global_search.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "gaitopt/opt/random_start.hpp"
#include "gaitopt/opt/result_order.hpp"

namespace gaitopt {
namespace {

// Offset of the restarts' generator seed from the starts' (any fixed value: a distinct
// stream, the same on every platform).
constexpr std::uint64_t kRetryStream = 0x9E3779B97F4A7C15ULL;

double criterionOf(const OptimizationResult& r, Criterion c) {
  return criterionValue(r.evaluation, c);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Whether `p` lies in the basin of one of the optima found so far.
bool insideKnownBasin(const GaitParameters& p, const std::vector<GlobalStart>& done,
                      const GlobalSearchSettings& s, const Parameterisation& par) {
  if (s.basin_radius <= 0.0) return false;
  for (const GlobalStart& d : done)
    if (!d.skipped && isOptimal(d.result) &&
        scaledRmsDistance(p, d.result.parameters, par) < s.basin_radius)
      return true;
  return false;
}

void clusterRuns(GlobalSearchResult& g, const GlobalSearchSettings& s, Criterion c) {
  std::vector<double> values;
  std::vector<int> index;
  for (const GlobalStart& st : g.starts)
    if (!st.skipped && isOptimal(st.result)) {
      values.push_back(criterionOf(st.result, c));
      index.push_back(st.index);
    }
  g.converged = static_cast<int>(values.size());
  g.clusters = clusterOptima(values, s.cluster_tolerance);
  for (OptimumCluster& cl : g.clusters)
    for (int& m : cl.members) m = index[m];
}

}  // namespace

std::vector<OptimumCluster> clusterOptima(const std::vector<double>& values, double rel_tol) {
  std::vector<int> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return values[a] < values[b]; });
  std::vector<OptimumCluster> clusters;
  for (int i : order) {
    if (clusters.empty() ||
        values[i] - clusters.back().criterion > rel_tol * std::abs(clusters.back().criterion))
      clusters.push_back({values[i], {}});
    clusters.back().members.push_back(i);
  }
  return clusters;
}

GlobalSearchSettings globalSearchSettings(int starts, std::uint64_t seed) {
  GlobalSearchSettings s;
  s.starts = starts;
  s.seed = seed;
  return s;
}

double scaledRmsDistance(const GaitParameters& a, const GaitParameters& b,
                         const Parameterisation& par) {
  const GaitParameters d = (a - b).cwiseQuotient(parameterScales(par));
  return std::sqrt(d.squaredNorm() / static_cast<double>(d.size()));
}

GlobalSearchResult globalSearch(const GaitEvaluator& ev, const OptimizationRequest& request,
                                const GlobalSearchSettings& s, std::ostream* log) {
  const Parameterisation& par = ev.options().parameterisation;
  GlobalSearchResult g;
  std::mt19937_64 rng(s.seed);
  std::mt19937_64 retry_rng(s.seed + kRetryStream);
  std::vector<double> times;
  for (int k = 1; k <= s.starts; ++k) {
    GlobalStart st;
    st.index = k;
    st.start = randomStart(request.initial, rng, par);
    st.skipped = insideKnownBasin(st.start, g.starts, s, par);
    if (log) *log << "--- global start " << k << "/" << s.starts << (st.skipped ? ": skipped (known basin)\n" : "\n");
    if (!st.skipped) {
      OptimizationRequest req = request;
      req.initial = st.start;
      req.solver.restore_feasibility = true;
      RestartedStart refined =
          improveByRestarts(ev, req, optimizeGait(ev, req, log), s.restart_settings, retry_rng, log);
      st.result = std::move(refined.result);
      st.restarts = refined.restarts;
      st.retries = refined.retries;
      st.perturbed_restarts = refined.perturbed_restarts;
      times.push_back(st.result.wall_time_s);
    }
    g.skipped += st.skipped ? 1 : 0;
    g.starts.push_back(std::move(st));
  }
  g.median_time_per_start_s = median(times);
  clusterRuns(g, s, request.criterion);
  if (g.clusters.empty()) {
    // Nothing converged: the run with the smallest violation is reported as it is.
    bool found = false;
    for (const GlobalStart& st : g.starts)
      if (!st.skipped &&
          (!found || betterResult(st.result, g.best, request.criterion, UnmetOrder::Violation))) {
        g.best = st.result;
        found = true;
      }
    return g;
  }
  g.best_start = g.clusters.front().members.front();
  const OptimizationResult& local = g.starts[g.best_start - 1].result;
  // Polish: the whole staged solve again from the best local optimum (a restart rebuilds the
  // quasi-Newton model there); kept only when it stays optimal and is not worse.
  OptimizationRequest req = request;
  req.initial = local.parameters;
  if (log) *log << "--- global polish from start " << g.best_start << "\n";
  const OptimizationResult polished = optimizeGait(ev, req, log);
  const bool keep = isOptimal(polished) &&
                    criterionOf(polished, request.criterion) <= criterionOf(local, request.criterion);
  g.best = keep ? polished : local;
  return g;
}

}  // namespace gaitopt
