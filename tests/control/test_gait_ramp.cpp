// Ramped export (gait_ramp.hpp): the per-sample constraint check against the evaluator's own
// constraint vector, the ramp's start rates and steps.
#include <catch2/catch.hpp>
#include <fstream>

#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/control/gait_ramp.hpp"
#include "gaitopt/math/chebyshev.hpp"
#include "test_default_gait.hpp"
#include "test_export_rows.hpp"
#include "test_files.hpp"

namespace gaitopt::test {
namespace {

double groupMax(const GaitEvaluation<double>& e, const ConstraintGroup& g, int first, int count) {
  double m = -1e300;
  for (int i = 0; i < count; ++i) m = std::max(m, e.g[g.offset + first + i]);
  return m;
}

double maximumOf(const std::vector<ConstraintMaximum>& maxima, const std::string& name) {
  for (const ConstraintMaximum& c : maxima)
    if (c.name == name) return c.value;
  FAIL("no maximum for " << name);
  return 0.0;
}

}  // namespace

TEST_CASE("Per-sample constraint check equals the evaluator's values at its DS nodes",
          "[export][ramp]") {
  const DefaultGait f;
  REQUIRE(f.evaluation.motion_computed);
  const auto step = std::make_shared<const GaitEvaluation<double>>(f.evaluation);
  const std::vector<WalkStepMotion> walk{{step, true}};
  const ConstraintLayout& layout = f.evaluator.layout();
  const auto ts = mappedNodes(f.evaluator.dsGrid(), 0.0, f.evaluation.motion.T_DS);
  for (int k = 0; k < ts.size(); ++k) {
    const PlannedSample s{ts(k), 0, 0.0, true,
                          sampleTrajectoryAt(f.evaluator, f.evaluation, Phase::DoubleSupport,
                                             ts(k))};
    const std::vector<ConstraintMaximum> m = sampleConstraintMaxima(f.evaluator, walk, {s});
    const auto& e = f.evaluation;
    CHECK(maximumOf(m, "torque_envelope_ds") ==
          Approx(groupMax(e, layout[kTorqueDS], 8 * k, 8)).margin(1e-9));
    CHECK(maximumOf(m, "joint_limits_ds") ==
          Approx(groupMax(e, layout[kJointLimitsDS], 8 * k, 8)).margin(1e-12));
    CHECK(maximumOf(m, "friction_cone_ds") ==
          Approx(groupMax(e, layout[kFrictionConeDS], 4 * k, 4)).margin(1e-9));
    CHECK(maximumOf(m, "normal_force_ds") ==
          Approx(groupMax(e, layout[kNormalForceDS], 2 * k, 2)).margin(1e-9));
    CHECK(maximumOf(m, "ds_reach_max") ==
          Approx(groupMax(e, layout[kDsReachMax], k, 1)).margin(1e-12));
    CHECK(maximumOf(m, "ds_monotone") ==
          Approx(groupMax(e, layout[kDsMonotone], k, 1)).margin(1e-12));
  }
}

TEST_CASE("A sample violating the friction cone is reported with its time and step",
          "[export][ramp]") {
  const DefaultGait f;
  const auto step = std::make_shared<const GaitEvaluation<double>>(f.evaluation);
  const std::vector<WalkStepMotion> walk{{step, true}};
  PlannedSample s{0.25, 0, 0.0, true,
                  sampleTrajectoryAt(f.evaluator, f.evaluation, Phase::SingleSupport, 0.1)};
  s.row.R1 = Vec2(300.0, 200.0);  // |Rx| − 0.6 Rz = 180 N (the gait's friction coefficient)
  const std::vector<ConstraintMaximum> m = sampleConstraintMaxima(f.evaluator, walk, {s});
  const std::vector<ConstraintMaximum> bad = violations(m, {});
  REQUIRE(bad.size() == 1);
  CHECK(bad[0].name == "friction_cone_ss");
  CHECK(bad[0].value == Approx(180.0).margin(1e-9));
  CHECK(bad[0].t == 0.25);
  // The gait's own level is tolerated, +1 % (kRampRelativeTolerance), not more.
  CHECK(violations(m, {{"friction_cone_ss", "N", 180.0, 0.0, 0}}).empty());
  CHECK(violations(m, {{"friction_cone_ss", "N", 178.3, 0.0, 0}}).empty());
  CHECK(violations(m, {{"friction_cone_ss", "N", 178.1, 0.0, 0}}).size() == 1);
}

TEST_CASE("Ramp start rates: slowest walkable first and last, linear in alphad squared",
          "[export][ramp]") {
  const DefaultGait f;
  const double a_star = f.evaluation.motion.alphadot_iSS;
  const double a_slow = slowestStartRate(f.evaluator, f.gait.parameters);
  // (3.56): the slowest start is the one whose σ² just reaches ε² at its minimum.
  CHECK(a_slow < 0.0);
  CHECK(a_slow > a_star);
  const std::vector<double> r = rampStartRates(a_star, a_slow, {3, 2, 2, true});
  REQUIRE(r.size() == 7);
  CHECK(r[0] == Approx(a_slow));
  CHECK(r[1] * r[1] - r[0] * r[0] == Approx((a_star * a_star - a_slow * a_slow) / 3));
  CHECK(r[2] * r[2] - r[1] * r[1] == Approx((a_star * a_star - a_slow * a_slow) / 3));
  CHECK(r[3] == a_star);
  CHECK(r[4] == a_star);
  CHECK(r[5] * r[5] == Approx(0.5 * (a_star * a_star + a_slow * a_slow)));
  CHECK(r[6] == Approx(a_slow));
  CHECK(rampStartRates(a_star, a_slow, {2, 2, 1, false}).size() == 3);
  // A start slower than the path allows is refused by the saturation check.
  GaitParameters p = f.gait.parameters;
  p(kAlphadotISS) = 0.5 * a_slow;
  CHECK(f.evaluator.evaluate(p).motion.alphadot_iSS == Approx(a_slow).margin(1e-12));
}

// The motion of step k of a walk at time t of `phase` (rest of the standing start: DS only).
TrajectoryRow rowOf(const GaitEvaluator& ev, const WalkStepMotion& s, Phase phase, double t) {
  return sampleTrajectoryAt(ev, *s.evaluation, phase, t);
}

TEST_CASE("The default gait ramps from rest to rest, every sample within the constraints",
          "[export][ramp]") {
  const DefaultGait f;
  const std::vector<WalkStepMotion> walk =
      rampedWalk(f.evaluator, f.gait.parameters, f.evaluation, {2, 2, 2, true});
  // Standing start, 2 ramp-in, 2 cyclic, 2 ramp-out steps.
  REQUIRE(walk.size() == 7);
  CHECK_FALSE(walk.front().single_support);
  const double a_star = f.evaluation.motion.alphadot_iSS;
  CHECK(walk[3].evaluation->motion.alphadot_iSS == a_star);
  CHECK(std::abs(walk[1].evaluation->motion.alphadot_iSS) < std::abs(a_star));
  CHECK(std::abs(walk[6].evaluation->motion.alphadot_iSS) < std::abs(a_star));
  // At rest, both feet down, at the start and at the end.
  const TrajectoryRow first = rowOf(f.evaluator, walk.front(), Phase::DoubleSupport, 0.0);
  const WalkStepMotion& last = walk.back();
  const TrajectoryRow end =
      rowOf(f.evaluator, last, Phase::DoubleSupport, last.evaluation->motion.T_DS);
  CHECK(first.qd.lpNorm<Eigen::Infinity>() <= 1e-9);
  CHECK(end.qd.lpNorm<Eigen::Infinity>() <= 1e-9);
  CHECK(first.R1(1) >= f.gait.options.min_normal_force);
  CHECK(first.R2(1) >= f.gait.options.min_normal_force);
  CHECK(std::abs(end.foot2(1)) <= 1e-9);
  // Junctions: DS end of step k = start of step k + 1 (same frame: leg 1 of a DS is the next
  // stance leg), positions and velocities to 1e-9.
  for (std::size_t k = 0; k + 1 < walk.size(); ++k) {
    INFO("junction after step " << k);
    const TrajectoryRow a = rowOf(f.evaluator, walk[k], Phase::DoubleSupport,
                                  walk[k].evaluation->motion.T_DS);
    const TrajectoryRow b = rowOf(f.evaluator, walk[k + 1], Phase::SingleSupport, 0.0);
    CHECK((a.q - b.q).lpNorm<Eigen::Infinity>() <= 1e-9);
    CHECK((a.qd - b.qd).lpNorm<Eigen::Infinity>() <= 1e-9);
    CHECK(std::isfinite(a.qdd.norm()));
  }
  // Every sample at 1 kHz holds the level-5 constraints (up to the gait's own level).
  const std::vector<PlannedSample> samples = sampleWalk(f.evaluator, walk, 1000.0);
  const auto gait = std::make_shared<const GaitEvaluation<double>>(f.evaluation);
  const std::vector<ConstraintMaximum> bad = violations(
      sampleConstraintMaxima(f.evaluator, walk, samples), gaitBaseline(f.evaluator, gait));
  for (const ConstraintMaximum& c : bad) FAIL_CHECK(c.name << " violated by " << c.value);
  // Accelerations bounded: within twice the cyclic gait's own peak.
  const auto peak = [](const std::vector<PlannedSample>& ss) {
    double m = 0.0;
    for (const PlannedSample& s : ss) m = std::max(m, s.row.qdd.lpNorm<Eigen::Infinity>());
    return m;
  };
  const double gait_peak = peak(sampleWalk(f.evaluator, {{gait, true}}, 1000.0));
  CHECK(peak(samples) <= 2.0 * gait_peak);
  // The export reads back to 1e-9.
  const std::vector<ExportRow> rows = exportWalk(f.evaluator, f.model, walk, samples, Leg::Left);
  ExportRequest req;
  req.steps = 2;
  req.rate = 1000.0;
  req.ramp_steps = 2;
  ScratchDir dir("ramp");
  const std::string path = dir.fresh("walk") + ".csv";
  std::ofstream(path) << exportCsv(exportMetadata(f.gait, f.evaluation, req), rows);
  const ExportCsvFile back = readExportCsv(path);
  REQUIRE(back.rows.size() == rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) requireRowsEqual(back.rows[i], rows[i], 1e-9);
}

}  // namespace gaitopt::test
