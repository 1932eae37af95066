// Constraints between the grid nodes: extra constraint points of the evaluator (the exchange
// method's continuous α and t), the 10× refined check, and the shared feasibility verdict.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "gaitopt/gait/feasibility.hpp"
#include "test_gait_support.hpp"

using namespace gaitopt;
using gaitopt::test::defaultGaitEvaluator;
using gaitopt::test::optimalStep;

namespace {

// Layout entry of point `point` (sub-entry `sub`) of a phase-wise group.
int entryOf(const ConstraintLayout& layout, int group, int point, int sub) {
  const ConstraintGroup& g = layout[group];
  return g.offset + (point - g.first_point) * g.per_point + sub;
}

}  // namespace

TEST_CASE("extra constraint points equal the refined grid's nodes there, with exact gradients",
          "[gait][between_nodes]") {
  const GaitParameters p = optimalStep();
  GaitOptions fine_options;
  fine_options.ss_nodes = 320;
  fine_options.ds_nodes = 160;
  const GaitEvaluator fine = defaultGaitEvaluator(fine_options);
  // Refined nodes 37 (SS) and 71 (DS) are no nodes of the default 32/16 grids.
  const int ks = 37, kd = 71;
  GaitOptions o;
  o.ss_extra_points = {fine.ssGrid().nodes()[ks]};
  o.ds_extra_points = {fine.dsGrid().nodes()[kd]};
  const GaitEvaluator ev = defaultGaitEvaluator(o);
  const GaitEvaluation<double> ef = fine.evaluate(p);
  const GaitGradient gr = ev.evaluateWithGradient(p);
  const GaitEvaluation<double>& e = gr.value;
  REQUIRE(e.motion_computed);
  double worst_value = 0.0, worst_gradient = 0.0;
  int checked = 0;
  for (int group = 0; group < kNumConstraintGroups; ++group) {
    const ConstraintGroup& g = ev.layout()[group];
    if (g.phase == ConstraintPhase::None) continue;
    const bool ss = g.phase == ConstraintPhase::SingleSupport;
    for (int sub = 0; sub < g.per_point; ++sub) {
      const int k = g.offset + g.count - g.per_point + sub;  // the one extra point: last block
      const int kf = entryOf(fine.layout(), group, ss ? ks : kd, sub);
      worst_value = std::max(worst_value, std::abs(e.g[k] - ef.g[kf]) / g.scale);
      for (int i = 0; i < kNumGaitParameters; ++i) {
        const double h = 1e-6 * std::max(1.0, std::abs(p(i)));
        GaitParameters pp = p, pm = p;
        pp(i) += h;
        pm(i) -= h;
        const double fd = (ev.evaluate(pp).g[k] - ev.evaluate(pm).g[k]) / (2.0 * h);
        worst_gradient =
            std::max(worst_gradient, std::abs(gr.dg(k, i) - fd) / std::max(1.0, std::abs(fd)));
        ++checked;
      }
    }
  }
  std::printf("  [between_nodes] extra points vs refined nodes: max scaled diff %.2e; %d "
              "gradient entries, max rel err %.2e\n", worst_value, checked, worst_gradient);
  CHECK(worst_value < 1e-8);
  CHECK(worst_gradient < 1e-5);
  CHECK(checked > 40 * kNumGaitParameters);
}
