// Ramped export (gait_ramp.hpp): the per-sample constraint check against the evaluator's own
// constraint vector, the ramp's start rates and steps, and the CLI's report of a ramp the
// gait's path cannot walk.
#include <catch2/catch.hpp>
#include <filesystem>

#include "gaitopt/export/gait_ramp.hpp"
#include "gaitopt/math/chebyshev.hpp"
#include "test_default_gait.hpp"
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
  s.row.R1 = Vec2(300.0, 200.0);  // |Rx| − 0.8 Rz = 140 N
  const std::vector<ConstraintMaximum> m = sampleConstraintMaxima(f.evaluator, walk, {s});
  const std::vector<ConstraintMaximum> bad = violations(m, {});
  REQUIRE(bad.size() == 1);
  CHECK(bad[0].name == "friction_cone_ss");
  CHECK(bad[0].value == Approx(140.0).margin(1e-9));
  CHECK(bad[0].t == 0.25);
  // The gait's own level is tolerated, not more.
  CHECK(violations(m, {{"friction_cone_ss", "N", 140.0, 0.0, 0}}).empty());
  CHECK(violations(m, {{"friction_cone_ss", "N", 139.9, 0.0, 0}}).size() == 1);
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

TEST_CASE("gaitopt export --ramp reports the constraint that the standing start violates",
          "[export][ramp]") {
  // On the default gait's path the standing start cannot reach the slowest walkable SS rate
  // within the DS constraints (README "gaitopt export", ramp): exit 3, nothing written.
  ScratchDir dir("ramp");
  const std::string gait = sourcePath("configs/gait/default_step.yaml");
  const std::string out = dir.fresh("walk") + ".csv";
  const CliRun run = runCli("export --gait " + quoted(gait) +
                            " --steps 2 --rate 250 --ramp --ramp-out none --out " + quoted(out));
  CHECK(run.exit_code == 3);
  CHECK_THAT(run.err, Catch::Matchers::Contains("no start from rest to alphad_iSS"));
  CHECK_FALSE(std::filesystem::exists(out));
  const CliRun bad = runCli("export --gait " + quoted(gait) + " --ramp --ramp-steps 1 --out " +
                            quoted(out));
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::Matchers::Contains("--ramp-steps"));
}

}  // namespace gaitopt::test
