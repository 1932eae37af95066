// W and C_E split at the kinks of their integrands (|Γ*_j ω_j|, max(0, P)): values against a
// 4× refined evaluation on the shipped optima, and the split points' implicit-function
// derivatives against central differences. (W's and C_E's own gradients are checked with the
// other criteria in test_evaluator.cpp and test_impact_gait.cpp.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
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

// The quadrature of the criteria is spectral on smooth integrands: these tests evaluate the
// shipped steps with viscous joint friction only. The smooth sign tanh(ω/ε) of dry friction
// (ε = 0.05 rad/s) is a boundary layer these grids do not resolve: on the default optimum W,
// C_E and C_Gamma are then 1e-4 to 7e-4 off a 4× refined evaluation (docs/formats/gait-file.md).
GaitOptions quadratureOptions(const GaitFile& g) {
  GaitOptions o = g.options;
  o.dry_friction = false;
  return o;
}

GaitEvaluation<double> evaluateWith(const GaitFile& g, int ss_factor, int ds_factor,
                                    int criteria_refinement) {
  GaitOptions o = quadratureOptions(g);
  o.ss_nodes *= ss_factor;
  o.ds_nodes *= ds_factor;
  o.criteria_refinement = criteria_refinement;
  const GaitEvaluator ev(g.robot, o, g.model_options);
  const GaitEvaluation<double> e = ev.evaluate(g.parameters);
  REQUIRE(e.motion_computed);
  return e;
}

// Relative differences of the criteria on the gait's own grids (SS × ss_factor, W and C_E on
// that SS grid × criteria_refinement) against 4× finer grids with the default refinement.
Refined refinementError(const GaitFile& g, int ss_factor, int criteria_refinement) {
  const GaitEvaluation<double> e = evaluateWith(g, ss_factor, 1, criteria_refinement);
  const GaitEvaluation<double> f = evaluateWith(g, 4, 4, GaitOptions{}.criteria_refinement);
  const auto rel = [](double a, double b) { return std::abs(a - b) / std::abs(b); };
  return {rel(e.W, f.W), rel(e.C_E, f.C_E), rel(e.C_Gamma, f.C_Gamma)};
}

const std::vector<std::string> kGaits = {
    "configs/gait/default_step.yaml",
    "tests/data/gait_optima/chesse_0.85.yaml",
    "tests/data/gait_optima/chevallereau_aoustin_0.75.yaml",
    "configs/gait/chesse_0.85_ipopt.yaml",
    "configs/gait/chevallereau_aoustin_0.75_impact.yaml",
};

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("W and C_E split at their kinks equal a 4x refined evaluation", "[gait][kinks]") {
  // Measured, relative to the 4x grids: with the default criteria_refinement 2 (W and C_E
  // sampled on the 65-node SS grid) W <= 2.2e-14 and C_E <= 1.7e-13 on the five gaits (target:
  // 1e-9). On the 33-node SS grid alone (refinement 1) the interpolant of
  // the integrands between the nodes leaves W up to 5.9e-7 off (the Chesse Ipopt point), and on
  // the last two gaits the motion itself is under-resolved (C_Gamma off by 2.3e-8, 9.9e-9; C_E by
  // 1.7e-6 on the Ipopt optimum), which Phi integrated on the finer grid removes. Before the
  // split (main 20ea839) W was off by 3.3e-3.
  for (const std::string& path : kGaits) {
    const GaitFile g = loadGaitFile(test::sourcePath(path));
    const Refined r = refinementError(g, 1, 2), plain = refinementError(g, 1, 1);
    std::printf("  [kinks] %s: vs 4x W %.1e, C_E %.1e (C_Gamma %.1e); SS grid alone: W %.1e, "
                "C_E %.1e\n",
                path.c_str(), r.rel_W, r.rel_C_E, r.rel_C_Gamma, plain.rel_W, plain.rel_C_E);
    INFO(path);
    CHECK(r.rel_W <= 1e-12);
    CHECK(r.rel_C_E <= 1e-12);
    CHECK(r.rel_C_Gamma == plain.rel_C_Gamma);
    // What the refinement is for (the shipped Chesse Ipopt point: W 5.9e-7 off on the SS grid).
    if (path == "configs/gait/chesse_0.85_ipopt.yaml") CHECK(plain.rel_W > 1e-9);
  }
}

TEST_CASE("criteria_refinement changes W, C_E and their split points only", "[gait][kinks]") {
  // The optimiser solves a C_Gamma objective with criteria_refinement 1 (opt/optimizer.cpp):
  // every other value and derivative must be the same number.
  const GaitFile g = loadGaitFile(test::sourcePath(kGaits.front()));
  GaitOptions o = quadratureOptions(g);
  o.criteria_refinement = 2;
  const GaitEvaluator refined(g.robot, o, g.model_options);
  const GaitEvaluator plain = refined.withCriteriaRefinement(1);
  CHECK(plain.options().criteria_refinement == 1);
  const GaitGradient a = refined.evaluateWithGradient(g.parameters);
  const GaitGradient b = plain.evaluateWithGradient(g.parameters);
  REQUIRE(a.value.g.size() == b.value.g.size());
  for (std::size_t k = 0; k < a.value.g.size(); ++k) CHECK(sameBits(a.value.g[k], b.value.g[k]));
  CHECK(a.dg == b.dg);
  for (const auto& [x, y] : {std::pair{a.value.C_Gamma, b.value.C_Gamma},
                             {a.value.C_frott, b.value.C_frott},
                             {a.value.T_SS, b.value.T_SS},
                             {a.value.speed, b.value.speed}})
    CHECK(sameBits(x, y));
  CHECK(a.dC_Gamma == b.dC_Gamma);
  CHECK(a.dC_frott == b.dC_frott);
  CHECK(a.value.W != b.value.W);
  CHECK(std::abs(a.value.W - b.value.W) <= 1e-8 * a.value.W);
  CHECK(a.value.C_E != b.value.C_E);
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
  for (const auto& c : cases) {
    const GaitEvaluator& ev = c.first;  // references, not a structured binding: C++17 lambdas
                                        // (clang) cannot capture one
    const GaitParameters& p = c.second;
    const GaitGradient gr = ev.evaluateWithGradient(p);
    const std::vector<double>& kinks = gr.value.criteria_kinks;
    REQUIRE(kinks.size() > 2);
    REQUIRE(gr.dcriteria_kinks.rows() == static_cast<int>(kinks.size()));
    if (gr.value.ss_criteria_kinks < static_cast<int>(kinks.size())) ++with_ds_kinks;
    for (int i = 0; i < ev.numParameters(); ++i) {
      if (!ev.options().parameterisation.isUsed(i)) continue;
      // Central differences with steps h and h/2, Richardson-extrapolated: the impact gait's
      // split points are so curved that one step of 1e-6 is off by up to 3e-5 relative.
      const double h = 1e-6 * std::max(1.0, std::abs(p(i)));
      const auto central = [&ev, &p, &kinks, i](double step) {
        GaitParameters pp = p, pm = p;
        pp(i) += step;
        pm(i) -= step;
        const std::vector<double> kp = ev.evaluate(pp).criteria_kinks;
        const std::vector<double> km = ev.evaluate(pm).criteria_kinks;
        REQUIRE(kp.size() == kinks.size());  // no kink appears or vanishes within ±step
        REQUIRE(km.size() == kinks.size());
        std::vector<double> d(kinks.size());
        for (std::size_t k = 0; k < kinks.size(); ++k) d[k] = (kp[k] - km[k]) / (2.0 * step);
        return d;
      };
      const std::vector<double> coarse = central(h), fine = central(0.5 * h);
      for (std::size_t k = 0; k < kinks.size(); ++k) {
        const double fd = (4.0 * fine[k] - coarse[k]) / 3.0;
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
