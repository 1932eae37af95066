// The DS level-5 constraints between the DS nodes (gait/ds_interval_maxima.hpp) on the C&A
// 0.75 m/s optimum of main, whose force split switches branch four times inside the DS: the
// interval maxima against the exact constraint on a nested 16x finer grid, and their
// gradients (interior piece maxima, switch times, nodes) against central differences.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "gaitopt/gait/ds_interval_maxima.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "test_support.hpp"

namespace {

using gaitopt::DsIntervalMaxima;
using gaitopt::DsIntervalMaximum;
using gaitopt::GaitEvaluator;
using gaitopt::GaitFile;

constexpr int kDsGroups[] = {gaitopt::kTorqueDS, gaitopt::kJointLimitsDS,
                             gaitopt::kFrictionConeDS, gaitopt::kNormalForceDS,
                             gaitopt::kDsMonotone};

GaitFile caOptimum(int ds_nodes) {
  GaitFile g = gaitopt::loadGaitFile(
      gaitopt::test::sourcePath("tests/data/gait_optima/chevallereau_aoustin_0.75.yaml"));
  g.options.ds_nodes = ds_nodes;
  return g;
}

// Whether a switch time lies between DS nodes j and j + 1.
bool containsSwitch(const GaitEvaluator& ev, const gaitopt::GaitEvaluation<double>& e, int j) {
  const double lo = 0.5 * (1.0 - ev.dsGrid().nodes()[j]) * e.T_DS;
  const double hi = 0.5 * (1.0 - ev.dsGrid().nodes()[j + 1]) * e.T_DS;
  for (double t : e.ds_pieces.switch_times)
    if (t > lo && t < hi) return true;
  return false;
}

}  // namespace

TEST_CASE("DS interval maxima follow the constraints through the force-split switches",
          "[gait][between_nodes]") {
  constexpr int kFine = 16;  // Lobatto grids nest: every 16th fine node is a coarse node
  const GaitFile g = caOptimum(8);
  const GaitEvaluator ev(g.robot, g.options, g.model_options);
  gaitopt::GaitOptions fine_options = g.options;
  fine_options.ds_nodes *= kFine;
  const GaitEvaluator fine(g.robot, fine_options, g.model_options);
  const auto e = ev.evaluate(g.parameters);
  const auto f = fine.evaluate(g.parameters);
  REQUIRE(e.motion_computed);
  REQUIRE(e.ds_pieces.switch_times.size() >= 2);
  REQUIRE(e.ds_piece_g.size() == e.ds_pieces.switch_times.size() + 1);
  DsIntervalMaxima maxima(ev);
  REQUIRE(maxima.update(e));
  int compared = 0, at_switch = 0, in_piece = 0;
  double worst = 0.0;
  for (int id : kDsGroups) {
    const gaitopt::ConstraintGroup& cg = ev.layout()[id];
    const gaitopt::ConstraintGroup& fg = fine.layout()[id];
    const double scale = gaitopt::constraintGroupScale(id, ev.model());
    for (int sub = 0; sub < cg.per_point; ++sub)
      for (int j = 0; j < ev.dsGrid().degree(); ++j) {
        double scan = -INFINITY;
        for (int k = kFine * j; k <= kFine * (j + 1); ++k)
          scan = std::max(scan, f.g[fg.offset + k * fg.per_point + sub]);
        const DsIntervalMaximum& m = maxima.maximum(id, sub, j);
        INFO(cg.name << "[" << sub << "], interval " << j << ": " << m.value << " (piece "
                     << m.piece << ", s " << m.s << "), fine grid " << scan);
        // Not below the exact values on the fine grid, and above them by no more than the
        // error of a degree-8 piece interpolant (and the curvature between fine nodes).
        CHECK(m.value >= scan - 1e-9 * scale);
        CHECK(m.value <= scan + 1e-3 * scale);
        worst = std::max(worst, std::abs(m.value - scan) / scale);
        ++compared;
        if (m.piece >= 0) ++(containsSwitch(ev, e, j) ? at_switch : in_piece);
      }
  }
  INFO("worst |max - fine grid| / scale " << worst);
  CHECK(compared == 23 * 8);
  CHECK(at_switch >= 1);  // maxima on a piece, in intervals cut by a switch time
  CHECK(in_piece >= 1);
}

TEST_CASE("DS interval maximum gradients equal central differences", "[gait][between_nodes]") {
  const GaitFile g = caOptimum(6);
  const GaitEvaluator ev(g.robot, g.options, g.model_options);
  const gaitopt::GaitGradient gr = ev.evaluateWithGradient(g.parameters);
  REQUIRE(gr.dds_piece_g.size() == gr.value.ds_piece_g.size());
  REQUIRE(gr.value.ds_pieces.switch_times.size() >= 2);
  DsIntervalMaxima at(ev), plus(ev), minus(ev);
  REQUIRE(at.update(gr.value));
  const gaitopt::Parameterisation& par = ev.options().parameterisation;
  int checked = 0, skipped = 0, at_switch = 0, in_piece = 0, at_node = 0, used = 0;
  double worst = 0.0;
  std::string worst_what;
  for (int i = 0; i < par.size(); ++i) {
    if (!par.isUsed(i)) continue;
    ++used;
    const double h = 1e-6 * std::max(1.0, std::abs(g.parameters(i)));
    gaitopt::GaitParameters pp = g.parameters, pm = g.parameters;
    pp(i) += h;
    pm(i) -= h;
    REQUIRE(plus.update(ev.evaluate(pp)));
    REQUIRE(minus.update(ev.evaluate(pm)));
    for (int id : kDsGroups)
      for (int sub = 0; sub < ev.layout()[id].per_point; ++sub)
        for (int j = 0; j < ev.dsGrid().degree(); ++j) {
          const double v0 = at.maximum(id, sub, j).value;
          const double vp = plus.maximum(id, sub, j).value, vm = minus.maximum(id, sub, j).value;
          const double fd = (vp - vm) / (2.0 * h);
          const double scale = std::max(1.0, std::abs(fd));
          // A change of the maximising candidate within ±h is a kink: FD is unreliable there.
          if (std::abs((vp - v0) / h - (v0 - vm) / h) > 1e-3 * scale) {
            ++skipped;
            continue;
          }
          const double ad = at.gradient(id, sub, j, gr)(i);
          const double err = std::abs(ad - fd) / scale;
          INFO(ev.layout()[id].name << "[" << sub << "], interval " << j << ", parameter " << i
                                    << ": AD " << ad << ", FD " << fd);
          CHECK(err <= 1e-5);
          if (err > worst) {
            worst = err;
            worst_what = ev.layout()[id].name;
          }
          ++checked;
          const DsIntervalMaximum& m = at.maximum(id, sub, j);
          if (m.piece < 0) ++at_node;
          else ++(containsSwitch(ev, gr.value, j) ? at_switch : in_piece);
        }
  }
  INFO("checked " << checked << ", skipped " << skipped << ", worst " << worst << " ("
                  << worst_what << ")");
  CHECK(checked >= used * 23 * 6 * 3 / 4);
  // Per parameter, at least one maximum on a piece in an interval cut by a switch time, one
  // on a piece elsewhere and one at a node.
  CHECK(at_switch >= used);
  CHECK(in_piece >= used);
  CHECK(at_node >= used);
}

TEST_CASE("A gradient without the DS piece derivatives is the same gradient otherwise",
          "[gait][between_nodes]") {
  const GaitFile g = caOptimum(6);
  const GaitEvaluator ev(g.robot, g.options, g.model_options);
  const gaitopt::GaitGradient full = ev.evaluateWithGradient(g.parameters);
  const gaitopt::GaitGradient nodes = ev.evaluateWithGradient(g.parameters, false);
  REQUIRE(full.value.ds_pieces.switch_times.size() >= 2);
  REQUIRE(full.dds_piece_g.size() == full.value.ds_piece_g.size());
  CHECK(nodes.dds_piece_g.empty());
  // The values still carry the piece samples (the interval maxima need them).
  CHECK(nodes.value.ds_piece_g.size() == full.value.ds_piece_g.size());
  CHECK(nodes.dg == full.dg);
  CHECK(nodes.dC_Gamma == full.dC_Gamma);
  CHECK(nodes.dW == full.dW);
  CHECK(nodes.dspeed == full.dspeed);
  CHECK(nodes.dcriteria_kinks == full.dcriteria_kinks);
  DsIntervalMaxima maxima(ev);
  REQUIRE(maxima.update(nodes.value));
  // Some interval's maximum lies on a piece: its gradient needs the piece derivatives.
  bool refused = false;
  for (int j = 0; j < ev.dsGrid().degree() && !refused; ++j)
    for (int sub = 0; sub < ev.layout()[gaitopt::kNormalForceDS].per_point; ++sub) {
      if (maxima.maximum(gaitopt::kNormalForceDS, sub, j).piece < 0) continue;
      CHECK_THROWS_WITH(maxima.gradient(gaitopt::kNormalForceDS, sub, j, nodes),
                        Catch::Contains("without the DS piece derivatives"));
      CHECK(maxima.gradient(gaitopt::kNormalForceDS, sub, j, full).size() == ev.numParameters());
      refused = true;
      break;
    }
  CHECK(refused);
}
