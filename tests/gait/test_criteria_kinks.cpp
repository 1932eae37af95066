// W and C_E split at the kinks of their integrands (|Γ*_j ω_j|, max(0, P)): values against a
// 4× refined evaluation on the shipped optima, and the split points' implicit-function
// derivatives against central differences. (W's and C_E's own gradients are checked with the
// other criteria in test_evaluator.cpp and test_impact_gait.cpp.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "test_gait_support.hpp"

using namespace gaitopt;

namespace {

struct Refined {
  double rel_W, rel_C_E, rel_C_Gamma;
};

// Relative differences of one gait's criteria between its own grids and grids `factor` × finer.
Refined refinementError(const GaitFile& g, int factor) {
  GaitOptions fine_options = g.options;
  fine_options.ss_nodes *= factor;
  fine_options.ds_nodes *= factor;
  const GaitEvaluation<double> e =
      GaitEvaluator(g.robot, g.options, g.model_options).evaluate(g.parameters);
  const GaitEvaluation<double> f =
      GaitEvaluator(g.robot, fine_options, g.model_options).evaluate(g.parameters);
  REQUIRE(e.motion_computed);
  REQUIRE(f.motion_computed);
  const auto rel = [](double a, double b) { return std::abs(a - b) / std::abs(b); };
  return {rel(e.W, f.W), rel(e.C_E, f.C_E), rel(e.C_Gamma, f.C_Gamma)};
}

}  // namespace

TEST_CASE("W and C_E split at their kinks equal a 4x refined evaluation", "[gait][kinks]") {
  // The C_Gamma optima of the three shipped configs (before the split: W off by 3.3e-3,
  // 7.8e-4, 1.6e-3 relative, C_E by 5e-6, 3.3e-4, 6.7e-4).
  for (const std::string path :
       {"configs/gait/default_step.yaml", "tests/data/gait_optima/chesse_0.85.yaml",
        "tests/data/gait_optima/chevallereau_aoustin_0.75.yaml"}) {
    const GaitFile g = loadGaitFile(test::sourcePath(path));
    const Refined r = refinementError(g, 4);
    std::printf("  [kinks] %s: vs 4x W %.1e, C_E %.1e (C_Gamma %.1e)\n", path.c_str(), r.rel_W,
                r.rel_C_E, r.rel_C_Gamma);
    INFO(path);
    CHECK(r.rel_W <= 1e-9);
    CHECK(r.rel_C_E <= 1e-9);
  }
}

TEST_CASE("W and C_E split at their kinks are as accurate as C_Gamma where the motion limits it",
          "[gait][kinks]") {
  // On these two optima C_Gamma itself (no kink) differs from the 4x refined evaluation by ~1e-8:
  // the 33-node SS interpolant of the motion limits every criterion, so the bound is C_Gamma's
  // own error (times 10, W's and C_E's integrands being less smooth) and it is stated, not hidden.
  for (const std::string path : {"configs/gait/chesse_0.85_ipopt.yaml",
                                 "configs/gait/chevallereau_aoustin_0.75_impact.yaml"}) {
    const GaitFile g = loadGaitFile(test::sourcePath(path));
    const Refined r = refinementError(g, 4);
    std::printf("  [kinks] %s: vs 4x W %.1e, C_E %.1e (C_Gamma %.1e)\n", path.c_str(), r.rel_W,
                r.rel_C_E, r.rel_C_Gamma);
    INFO(path);
    CHECK(r.rel_C_Gamma > 1e-9);  // else the first test case's 1e-9 applies
    CHECK(r.rel_W <= 10.0 * r.rel_C_Gamma);
    CHECK(r.rel_C_E <= 10.0 * r.rel_C_Gamma);
    // The refined reference itself: 4x and 8x agree far below that floor.
    GaitFile fine = g;
    fine.options.ss_nodes *= 4;
    fine.options.ds_nodes *= 4;
    const Refined ref = refinementError(fine, 2);
    CHECK(ref.rel_W <= 1e-11);
    CHECK(ref.rel_C_E <= 1e-11);
  }
}

TEST_CASE("split points of W and C_E: implicit-function derivatives equal finite differences",
          "[gait][kinks]") {
  std::vector<std::pair<GaitEvaluator, GaitParameters>> cases;
  cases.emplace_back(test::defaultGaitEvaluator(), test::optimalStep());
  cases.emplace_back(test::defaultGaitEvaluator(), test::definedStep());  // DS branch switch
  const GaitFile impact =
      loadGaitFile(test::sourcePath("configs/gait/chevallereau_aoustin_0.75_impact.yaml"));
  cases.emplace_back(GaitEvaluator(impact.robot, impact.options, impact.model_options),
                     impact.parameters);
  int checked = 0, with_ds_kinks = 0;
  double worst = 0.0;
  for (const auto& [ev, p] : cases) {
    const GaitGradient gr = ev.evaluateWithGradient(p);
    const std::vector<double>& kinks = gr.value.criteria_kinks;
    REQUIRE(kinks.size() > 2);
    REQUIRE(gr.dcriteria_kinks.rows() == static_cast<int>(kinks.size()));
    if (gr.value.ss_criteria_kinks < static_cast<int>(kinks.size())) ++with_ds_kinks;
    for (int i = 0; i < ev.numParameters(); ++i) {
      if (!ev.options().parameterisation.isUsed(i)) continue;
      const double h = 1e-6 * std::max(1.0, std::abs(p(i)));
      GaitParameters pp = p, pm = p;
      pp(i) += h;
      pm(i) -= h;
      const std::vector<double> kp = ev.evaluate(pp).criteria_kinks;
      const std::vector<double> km = ev.evaluate(pm).criteria_kinks;
      REQUIRE(kp.size() == kinks.size());  // no kink appears or vanishes within ±h
      REQUIRE(km.size() == kinks.size());
      for (std::size_t k = 0; k < kinks.size(); ++k) {
        const double fd = (kp[k] - km[k]) / (2.0 * h);
        const double ad = gr.dcriteria_kinks(static_cast<int>(k), i);
        const double err = std::abs(ad - fd) / std::max(1.0, std::abs(fd));
        INFO("kink " << k << " at " << kinks[k] << ", parameter " << i << ": AD " << ad
                     << ", FD " << fd);
        CHECK(err < 1e-6);
        worst = std::max(worst, err);
        ++checked;
      }
    }
  }
  std::printf("  [kinks] split-point derivatives: %d entries, max rel err %.1e\n", checked, worst);
  CHECK(with_ds_kinks >= 1);
}
