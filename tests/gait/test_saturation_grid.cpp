// The saturation (3.56) of the SS start rate and the grid: α̇_iSS is capped at
// alphadot_margin beyond the no-falling-back limit −√(−Φ_min)/f_iSS, with Φ_min the minimum of
// Φ's interpolant over the whole SS. Where the cap binds and Φ is lowest between two nodes, a
// minimum over the nodes alone would make the motion depend on the grid: the 10× finer grids
// of the feasibility verdict (gait/feasibility.hpp) would find a lower Φ, a faster α̇_iSS,
// another speed and other forces, and could fail where every row of the optimiser holds. Here:
// the same α̇_iSS and speed on 33 to 321 SS nodes, the verdict's finer check agreeing with the
// rows between the nodes, and the gradients of such a step against finite differences.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "gaitopt/gait/constraint_summary.hpp"
#include "gaitopt/gait/ds_interval_maxima.hpp"
#include "gaitopt/gait/feasibility.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/math/chebyshev_maxima.hpp"
#include "test_gradient_check.hpp"
#include "test_support.hpp"

using namespace gaitopt;

namespace {

// configs/default.yaml's problem at 0.15 m/s: a step of the 10-speed library sweep where the
// cap binds, Φ is lowest between two SS nodes and a DS normal force touches R_min between the
// DS nodes.
GaitFile slowStep() {
  GaitFile g = loadGaitFile(test::sourcePath("configs/gait/default_step.yaml"));
  g.options.target_speed = 0.15;
  g.parameters.resize(kNumGaitParameters);
  g.parameters << -0.0091112493971792809, -2.8134147651211547, 1.410724821332735,
      0.15257551546364648, -0.10812974530653419, -2.7479857704505757, 1.3475765949907572,
      -2.7211188240252087, 1.4595552421096583, 0.02598111398699509, 0.038400695020211165,
      -0.24154662039270006, -0.71416988290330574, -0.25634804230603475, 0.77865575469583059,
      0.0382901207668188, 0.32521383643502572;
  return g;
}

// The slow step, and the shipped impact gait, planned with alphadot_margin 0.45 so that the cap
// binds (its single support starts at the cyclic rate of the impact otherwise).
std::vector<GaitFile> saturatedSteps() {
  return {slowStep(), loadGaitFile(test::sourcePath("configs/gait/default_impact.yaml"))};
}

GaitEvaluator ev(const GaitFile& g) { return GaitEvaluator(g.robot, g.options, g.model_options); }

GaitEvaluator refined(const GaitFile& g, int factor) {
  GaitOptions o = g.options;
  o.ss_nodes *= factor;
  o.ds_nodes *= factor;
  return GaitEvaluator(g.robot, o, g.model_options);
}

// The largest normal_force_ds row between the DS nodes, as the optimiser holds it (N).
double dsNormalForceRows(const GaitEvaluator& ev, const GaitEvaluation<double>& e) {
  DsIntervalMaxima maxima(ev);
  REQUIRE(maxima.update(e));
  double worst = -std::numeric_limits<double>::infinity();
  for (int foot = 0; foot < 2; ++foot)
    for (int j = 0; j < ev.dsGrid().degree(); ++j)
      worst = std::max(worst, maxima.maximum(kNormalForceDS, foot, j).value);
  return worst;
}

std::string withoutIndex(const std::string& name) { return name.substr(0, name.find('[')); }

}  // namespace

TEST_CASE("steps whose SS start rate is saturated (3.56) where Phi is lowest between nodes",
          "[gait]") {
  for (const GaitFile& g : saturatedSteps()) {
    const GaitEvaluator ev(g.robot, g.options, g.model_options);
    const GaitEvaluation<double> e = ev.evaluate(g.parameters);
    REQUIRE(e.motion_computed);
    const double lowest_node = e.motion.ss_phi.minCoeff();
    const double phi_min = interpolantMinimum(ev.ssGrid(), e.motion.ss_phi);
    std::printf("  [gait] %s: alphadot_iSS %.9f, min Phi %.6f (lowest node %.6f)\n",
                g.path.c_str(), e.motion.alphadot_iSS, phi_min, lowest_node);
    INFO(g.path << " alphadot_iSS " << e.motion.alphadot_iSS);
    // The cap binds: the start rate is the limit of (3.56) with the interpolant's minimum.
    const double limit = -std::sqrt(-phi_min) / e.motion.f_iSS - g.options.alphadot_margin;
    CHECK(e.motion.alphadot_iSS == Approx(limit).epsilon(1e-14));
    CHECK(phi_min < lowest_node - 1e-3);  // lower between two nodes than at any node
  }
  const GaitFile slow = slowStep();
  CHECK(ev(slow).evaluate(slow.parameters).motion.alphadot_iSS < slow.parameters[kAlphadotISS] - 0.01);
}

TEST_CASE("the saturated SS start rate (3.56) does not depend on the grid", "[gait]") {
  for (const GaitFile& g : saturatedSteps()) {
    const GaitEvaluation<double> coarse = refined(g, 1).evaluate(g.parameters);
    for (int factor = 2; factor <= kBetweenNodesRefinement; ++factor) {
      const GaitEvaluation<double> fine = refined(g, factor).evaluate(g.parameters);
      const int nodes = g.options.ss_nodes * factor + 1;
      INFO(g.path << ", " << nodes << " SS nodes");
      std::printf("  [gait] %s, %d SS nodes: alphadot_iSS %+.3e, speed %+.3e against %d\n",
                  g.path.c_str(), nodes, fine.motion.alphadot_iSS - coarse.motion.alphadot_iSS,
                  fine.speed - coarse.speed, g.options.ss_nodes + 1);
      CHECK(fine.motion.alphadot_iSS == Approx(coarse.motion.alphadot_iSS).epsilon(1e-12));
      CHECK(fine.speed == Approx(coarse.speed).epsilon(1e-12));
    }
  }
}

TEST_CASE("the DS normal-force rows between the nodes hold what the finer check checks",
          "[gait]") {
  const GaitFile g = slowStep();
  const GaitEvaluator ev(g.robot, g.options, g.model_options);
  const GaitEvaluation<double> e = ev.evaluate(g.parameters);
  const double rows = dsNormalForceRows(ev, e);
  const BetweenNodesCheck fine = checkBetweenNodes(ev, g.parameters);
  const double scale = constraintGroupScale(kNormalForceDS, ev.model());
  const double checked = fine.group_worst_scaled[kNormalForceDS] * scale;
  std::printf("  [gait] normal_force_ds between the nodes: rows %+.6f N, 10x finer check %+.6f N\n",
              rows, checked);
  // The rows' maxima lie between the 160 nodes of the finer check too: they may exceed it, by
  // little, and never fall short of it by more than its tolerance.
  CHECK(rows >= checked - kFeasibilityTolerance * scale);
  CHECK(rows - checked < 0.01);
}

TEST_CASE("exact gradients of a step saturated (3.56) between the nodes equal finite differences",
          "[gait][derivatives]") {
  const GaitFile g = slowStep();
  const GaitEvaluator ev(g.robot, g.options, g.model_options);
  const GaitGradient grad = ev.evaluateWithGradient(g.parameters);
  REQUIRE(grad.value.motion_computed);
  std::vector<test::GradientOutput> outputs = {
      {"T_SS", [](const GaitEvaluation<double>& e) { return e.T_SS; }, grad.dT_SS},
      {"speed", [](const GaitEvaluation<double>& e) { return e.speed; }, grad.dspeed},
      {"C_Gamma", [](const GaitEvaluation<double>& e) { return e.C_Gamma; }, grad.dC_Gamma},
  };
  for (const ConstraintGroup& group : ev.layout().groups())
    for (int k = group.offset; k < group.offset + group.count; ++k)
      if (grad.value.state[k] != ConstraintState::NotComputed)
        outputs.push_back({group.name + "[" + std::to_string(k - group.offset) + "]",
                           [k](const GaitEvaluation<double>& e) { return e.g[k]; },
                           grad.dg.row(k).transpose()});
  const test::GradientCheck r = test::checkGradient(ev, g.parameters, outputs, withoutIndex);
  std::printf("  [gait] saturated step: %d gradient entries checked, %d skipped, max err %.3e "
              "at %s\n",
              r.checked, r.skipped, r.worst, r.worst_what.c_str());
  INFO(r.failures);
  CHECK(r.failed == 0);
  CHECK(r.skipped_by_output.count("speed") == 0);
  CHECK(r.skipped_by_output.count("T_SS") == 0);
  CHECK(r.checked > 0.9 * (r.checked + r.skipped));
  // The speed depends on the start rate only through the cap, hence through Φ_min.
  CHECK(grad.dspeed(kAlphadotISS) == 0.0);
}
