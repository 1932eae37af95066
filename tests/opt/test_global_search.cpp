// Multi-start global search (opt/global_search.hpp): clustering of local optima on synthetic
// lists, the basin distance, the settings of --global K --seed S, a small --global run on the
// default problem against the plain optimum, and seeded reproducibility.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "test_viscous_config.hpp"
#include "gaitopt/opt/gait_problem.hpp"
#include "gaitopt/opt/global_search.hpp"
#include "gaitopt/opt/optimizer.hpp"
#include "test_support.hpp"

namespace {

using gaitopt::OptimumCluster;

const std::string kDefaultConfig = gaitopt::test::sourcePath("configs/default.yaml");

// With dry friction, 3 starts cluster 0.4 % above the plain run's optimum.
struct DefaultProblem {
  gaitopt::OptimizeConfig config = gaitopt::test::viscousConfig("default.yaml");
  gaitopt::GaitEvaluator evaluator{config.robot, config.options, config.model_options};
  gaitopt::OptimizationRequest request() const {
    gaitopt::OptimizationRequest r = gaitopt::optimizationRequest(
        config, gaitopt::configuredInitialGuess(config, evaluator.model()));
    r.solver.print_every = 0;
    return r;
  }
};

const DefaultProblem& defaultProblem() {
  static const DefaultProblem p;
  return p;
}

std::vector<int> sizes(const std::vector<OptimumCluster>& clusters) {
  std::vector<int> s;
  for (const OptimumCluster& c : clusters) s.push_back(c.size());
  return s;
}

}  // namespace

TEST_CASE("global: clusters of a synthetic list of optima", "[optimize]") {
  // 100 and 100.05 (0.05 %) together; 100.2 (0.2 %) apart; 120, 120.1 together; order of the
  // input does not matter, members are indices into it in increasing value.
  const std::vector<double> values = {120.1, 100.05, 100.2, 100.0, 120.0, 100.099};
  const std::vector<OptimumCluster> c = gaitopt::clusterOptima(values, 1e-3);
  REQUIRE(c.size() == 3);
  CHECK(sizes(c) == std::vector<int>{3, 1, 2});
  CHECK(c[0].criterion == 100.0);
  CHECK(c[0].members == std::vector<int>{3, 1, 5});
  CHECK(c[1].criterion == 100.2);
  CHECK(c[1].members == std::vector<int>{2});
  CHECK(c[2].criterion == 120.0);
  CHECK(c[2].members == std::vector<int>{4, 0});
  // The tolerance is relative to the cluster's lowest value, not chained from value to value.
  CHECK(sizes(gaitopt::clusterOptima({1.0, 1.0009, 1.0018, 1.0027}, 1e-3)) ==
        std::vector<int>{2, 2});
  CHECK(gaitopt::clusterOptima({}, 1e-3).empty());
  CHECK(sizes(gaitopt::clusterOptima({5.0, 5.0, 5.0}, 0.0)) == std::vector<int>{3});
}

TEST_CASE("global: the basin distance is the RMS of the scaled differences", "[optimize]") {
  const gaitopt::Parameterisation par;
  const gaitopt::GaitParameters s = gaitopt::parameterScales(par);
  gaitopt::GaitParameters a = gaitopt::GaitParameters::Zero(par.size());
  gaitopt::GaitParameters b = a;
  b(0) = 2.0 * s(0);  // two scales on one of 17 parameters
  CHECK(gaitopt::scaledRmsDistance(a, b, par) == Approx(2.0 / std::sqrt(17.0)).epsilon(1e-12));
  b = a + s;  // one scale on every parameter
  CHECK(gaitopt::scaledRmsDistance(a, b, par) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("global: the settings of --global K --seed S are the library's defaults otherwise",
          "[optimize]") {
  // bench_optimize --global-per-start measures what users run only if both take these.
  const gaitopt::GlobalSearchSettings s = gaitopt::globalSearchSettings(5, 7);
  const gaitopt::GlobalSearchSettings d;
  CHECK(s.starts == 5);
  CHECK(s.seed == 7u);
  CHECK(s.cluster_tolerance == d.cluster_tolerance);
  CHECK(s.basin_radius == d.basin_radius);
  CHECK(s.basin_radius > 0.0);  // the basin skip is on, unlike bench_optimize's single starts
  CHECK(s.restart_settings.max_restarts == d.restart_settings.max_restarts);
  CHECK(s.restart_settings.max_retries == d.restart_settings.max_retries);
  CHECK(s.restart_settings.max_perturbed_restarts == d.restart_settings.max_perturbed_restarts);
  CHECK(s.restart_settings.perturbation == d.restart_settings.perturbation);
  CHECK(s.restart_settings.optimum_perturbation == d.restart_settings.optimum_perturbation);
}

TEST_CASE("global: a small multi-start run on the default problem finds the plain optimum",
          "[optimize]") {
  const DefaultProblem& d = defaultProblem();
  const gaitopt::OptimizationResult plain = gaitopt::optimizeGait(d.evaluator, d.request());
  REQUIRE(plain.status == gaitopt::OptimizationStatus::Optimal);
  const double c_plain = gaitopt::criterionValue(plain.evaluation, d.config.criterion);

  gaitopt::GlobalSearchSettings gs;
  gs.starts = gaitopt::test::lightTests() ? 2 : 3;
  gs.seed = 1;
  // The perturbed restarts have their own test (test_start_restarts.cpp); 3 staged solves
  // per optimal start are the sanitizer pass's largest cost here.
  if (gaitopt::test::lightTests()) gs.restart_settings.max_perturbed_restarts = 0;
  const gaitopt::GlobalSearchResult g = gaitopt::globalSearch(d.evaluator, d.request(), gs);
  REQUIRE(static_cast<int>(g.starts.size()) == gs.starts);
  REQUIRE_FALSE(g.clusters.empty());
  CHECK(g.best.status == gaitopt::OptimizationStatus::Optimal);
  const double c_best = gaitopt::criterionValue(g.best.evaluation, d.config.criterion);
  CHECK(std::abs(g.clusters.front().criterion - c_plain) <= 1e-3 * c_plain);
  CHECK(c_best <= g.clusters.front().criterion);
  CHECK(std::abs(c_best - c_plain) <= 1e-3 * c_plain);
  // Bookkeeping: every optimal optimised start is in exactly one cluster.
  int members = 0;
  for (const OptimumCluster& c : g.clusters) members += c.size();
  CHECK(members == g.converged);
  CHECK(g.converged + g.skipped <= gs.starts);
  CHECK(g.median_time_per_start_s > 0.0);
  CHECK(g.best_start == g.clusters.front().members.front());
  // Each optimised start was refined (start_restarts.hpp): an optimal one restarted at least
  // once, within the settings' bounds.
  for (const gaitopt::GlobalStart& st : g.starts) {
    if (st.skipped) continue;
    CHECK(st.restarts <= gs.restart_settings.max_restarts);
    CHECK(st.retries <= gs.restart_settings.max_retries);
    if (st.result.status == gaitopt::OptimizationStatus::Optimal) CHECK(st.restarts >= 1);
  }
}

TEST_CASE("global: a start inside a known basin is skipped", "[optimize]") {
  const DefaultProblem& d = defaultProblem();
  // The two starts of seed 1 are about one scale apart (RMS); a radius of 10 scales makes the
  // first optimum's basin cover the second start.
  gaitopt::GlobalSearchSettings gs;
  gs.starts = 2;
  gs.basin_radius = 10.0;
  if (gaitopt::test::lightTests()) gs.restart_settings.max_perturbed_restarts = 0;  // as above
  const gaitopt::GlobalSearchResult g = gaitopt::globalSearch(d.evaluator, d.request(), gs);
  REQUIRE(g.starts.size() == 2);
  REQUIRE(g.starts[0].result.status == gaitopt::OptimizationStatus::Optimal);
  CHECK_FALSE(g.starts[0].skipped);
  CHECK(g.starts[1].skipped);
  CHECK(g.skipped == 1);
  CHECK(g.converged == 1);
}
