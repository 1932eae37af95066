// The rocker_foot effect: synth's rolling-foot TRUE model (floating model with the
// rolling constraint) against the ankle-frame equations diagnose fits; the radius recovered
// from synthetic data; no rocker on point-foot data; the robot-file key.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "gaitopt/ident/diagnose.hpp"
#include "gaitopt/io/diagnosis_file.hpp"
#include "gaitopt/ident/synth.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/measured_data.hpp"
#include "gaitopt/io/robot_extensions.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "gaitopt/model/rocker_foot.hpp"
#include "test_files.hpp"
#include "test_ident_support.hpp"
#include "test_support.hpp"

using namespace gaitopt;
using Catch::Matchers::Contains;

namespace {

const GaitFile& gait() { return test::defaultStepGait(); }

MeasuredData synth(const std::vector<Effect>& effects, std::uint64_t seed, int steps, bool noise) {
  SynthOptions o;
  o.steps = steps;
  o.seed = seed;
  o.noise = noise;
  return synthesize(gait().robot, gait().parameters, gait().options, gait().model_options, effects, o);
}

double rms(const ResidualMatrix& r, int c, const std::vector<char>& rows) {
  double s = 0.0;
  int n = 0;
  for (Eigen::Index i = 0; i < r.rows(); ++i)
    if (rows[i] && std::isfinite(r(i, c))) {
      s += r(i, c) * r(i, c);
      ++n;
    }
  return n ? std::sqrt(s / n) : 0.0;
}

// Single-support rows away from the phase ends (the differentiator is one-sided there).
std::vector<char> innerSingleSupport(const PreparedData& p) {
  std::vector<char> rows(p.data.size(), 0);
  for (const Segment& s : p.segments)
    for (std::size_t i = s.begin; i < s.end; ++i)
      rows[i] = s.phase == Phase::SingleSupport && p.data.t[i] - p.data.t[s.begin] >= 0.03 &&
                p.data.t[s.end - 1] - p.data.t[i] >= 0.03;
  return rows;
}

}  // namespace

TEST_CASE("rocker contact: the contact point of the arc is at rest (rolling, no slip)", "[rocker]") {
  for (double slope : {0.0, 0.03}) {
    const double r = 0.2, alpha = 0.25, alphad = -1.3, h = 1e-6;
    const RockerContact<double> c = rockerContact(r, 0.0, slope, alpha, alphad, 0.0);
    // Material velocity of the contact point: v_A + ω × (P − A), ω = α̇ (tibia angle α − π/2).
    const Vec2 v = c.ankle_jacobian * alphad + alphad * Vec2(-c.contact_arm(1), c.contact_arm(0));
    CHECK(v.norm() < 1e-12);
    // The contact point lies on the ground line, r below the arc's centre.
    CHECK((c.contact_arm - r * Vec2(-std::sin(alpha), std::cos(alpha))).norm() == Approx(r));
    // ∂A/∂α against a finite difference of the contact point's travel: A = P − arm, P moves
    // along the ground by −r per radian.
    const RockerContact<double> cp = rockerContact(r, 0.0, slope, alpha + h, alphad, 0.0);
    const Vec2 ground(std::cos(slope), std::sin(slope));
    const Vec2 dA = (-r * h * ground - (cp.contact_arm - c.contact_arm)) / h;
    CHECK((dA - c.ankle_jacobian).norm() < 1e-6);
  }
}

TEST_CASE("synth rocker_foot: the rolling TRUE model satisfies the ankle-frame equations", "[rocker]") {
  const Effect rocker{EffectKind::RockerFoot, kNoJoint, 0.06};
  const MeasuredData with_cop = synth({rocker}, 7, 4, false);
  MeasuredData d = with_cop;
  d.has_cop = false;  // the α row with the model's foot moment
  const PreparedData p(d, test::exactSmoothing());
  const std::vector<char> rows = innerSingleSupport(p);
  const ResidualMatrix with = residuals(p, withEffects(gait().robot, {rocker}), gait().model_options, rows);
  const ResidualMatrix without = residuals(p, gait().robot, gait().model_options, rows);
  // Two formulations (floating model + rolling constraint in synth, ankle-frame pinned model in
  // diagnose) agree up to the smoothing differentiator's error.
  CHECK(rms(with, kAlphaRow, rows) < 0.02);
  for (int c = kGammaKneeLeft; c <= kGammaKneeRight; ++c) CHECK(rms(with, c, rows) < 0.15);
  CHECK(rms(with, kR1x, rows) < 0.25);
  CHECK(rms(with, kR1z, rows) < 0.25);
  // The point foot misses the moment of the rolling contact: r × α × weight, several N·m.
  CHECK(rms(without, kAlphaRow, rows) > 2.0);
  // With the centres of pressure that moment is measured: the α row no longer misses it (what
  // is left is second order in the tibia angle: synth places the contact r α from a standing
  // ankle, the rolling arc r sin α from a moving one), and the CoP travel tells the feet apart.
  const PreparedData pc(with_cop, test::exactSmoothing());
  const ResidualMatrix with_c = residuals(pc, withEffects(gait().robot, {rocker}), gait().model_options, rows);
  const ResidualMatrix without_c = residuals(pc, gait().robot, gait().model_options, rows);
  CHECK(rms(with_c, kAlphaRow, rows) < 0.25);
  CHECK(rms(without_c, kAlphaRow, rows) < 0.25);
  CHECK(rms(with_c, kCopX, rows) < 1e-4);
  CHECK(rms(without_c, kCopX, rows) > 0.003);  // r × the tibia's travel about its mean
}

TEST_CASE("diagnose recovers a hidden rocker_foot radius within 5 %", "[rocker]") {
  const Effect truth{EffectKind::RockerFoot, kNoJoint, 0.08};
  const Diagnosis d = diagnose(gait().robot, gait().model_options, synth({truth}, 21, 20, true));
  REQUIRE(!d.causes.empty());
  const Cause& c = d.causes[0];
  INFO("found " << effectLabel(c.effect) << " = " << c.effect.value << " +- " << c.stderr_);
  CHECK(effectLabel(c.effect) == "rocker_foot");
  CHECK(c.effect.value == Approx(truth.value).epsilon(0.05));
  CHECK(c.stderr_ < 0.05 * truth.value);
  CHECK(d.extended_robot.foot_radius == Approx(c.effect.value));
  CHECK(d.rms_reduction_pct[kCopX] > 50.0);
  CHECK_THAT(diagnosisReport(d), Contains("the point foot is the cause"));
}

TEST_CASE("diagnose: point-foot data give no rocker_foot", "[rocker]") {
  DiagnoseOptions o;
  o.kinds = {EffectKind::RockerFoot};
  const int seeds = test::lightTests() ? 2 : 5;
  for (int s = 0; s < seeds; ++s) {
    const Diagnosis d = diagnose(gait().robot, gait().model_options, synth({}, 300 + s, 20, true), o);
    INFO("seed " << 300 + s << ": fitted r = " << d.candidates.at(0).effect.value);
    CHECK(d.causes.empty());
    CHECK(std::abs(d.candidates.at(0).effect.value) < 0.005);
  }
}

TEST_CASE("robot file: foot_radius key, range-checked, written back", "[rocker]") {
  test::ScratchDir dir("rocker");
  const std::string base = test::readFile(test::sourcePath("configs/robot/rabbit_miossec.yaml"));
  const RobotParams r = loadRobot(dir.write(base + "foot_radius: 0.12\n", "rocker"));
  CHECK(r.foot_radius == 0.12);
  CHECK_THAT(robotExtensionsYaml(r), Contains("foot_radius: 0.12"));
  for (const char* bad : {"-0.01", "0.8", "2.0"}) {  // rabbit legs: 0.8 m
    const std::string path = dir.write(base + "foot_radius: " + bad + "\n", "bad");
    INFO(bad);
    CHECK_THROWS_WITH(loadRobot(path), Contains("foot_radius") && Contains("leg length"));
  }
}

