// diagnose on the shipped OpenSim walking trial imported by `gaitopt import-opensim`: the
// rocker foot named, held out across legs.
#include <catch2/catch.hpp>

#include <set>

#include "gaitopt/ident/diagnose.hpp"
#include "gaitopt/io/diagnosis_file.hpp"
#include "gaitopt/io/measured_data.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "test_opensim_data.hpp"
#include "test_support.hpp"

using namespace gaitopt;
using Catch::Matchers::Contains;

namespace {

const RobotParams& human() {
  static const RobotParams r = loadRobot(test::sourcePath("configs/robot/human_subject01.yaml"));
  return r;
}

// The shipped OpenSim trial imported by `gaitopt import-opensim` (the measured-data CSV) and
// read back.
const MeasuredData& subject01() {
  static test::ScratchDir dir("rocker_subject01");
  static const MeasuredData d = [] {
    const std::string path = dir.fresh("subject01") + ".csv";
    const test::CliRun run = test::runCli(
        "import-opensim --ik " + test::quoted(test::opensimIk()) + " --grf " +
        test::quoted(test::opensimGrf()) + " --trc " + test::quoted(test::opensimTrc()) +
        " --robot " + test::quoted(test::sourcePath("configs/robot/human_subject01.yaml")) +
        " --out " + test::quoted(path));
    REQUIRE(run.exit_code == 0);
    return readMeasuredCsv(path);
  }();
  return d;
}

}  // namespace

TEST_CASE("diagnose on the shipped OpenSim trial names the foot, held out across legs", "[rocker]") {
  const MeasuredData& d = subject01();
  for (int shift : {0, 1}) {
    DiagnoseOptions o;
    o.holdout = 2;  // steps alternate the stance leg: fit on one leg's stances, test on the other's
    o.holdout_shift = shift;
    const Diagnosis dg = diagnose(human(), ModelOptions{}, d, o);
    // The split is by leg: every fitted sample has one stance label, every held-out one the other.
    std::set<int> fit_legs, held_legs;
    for (std::size_t i = 0; i < d.size(); ++i)
      (dg.fit_rows[i] ? fit_legs : held_legs).insert(static_cast<int>(d.stance[i]));
    CHECK(fit_legs.size() == 1);
    CHECK(held_legs.size() == 1);
    CHECK(*fit_legs.begin() != *held_legs.begin());
    REQUIRE(!dg.causes.empty());
    const Cause& c = dg.causes[0];
    INFO("shift " << shift << ": " << effectLabel(c.effect) << " = " << c.effect.value);
    CHECK((c.effect.kind == EffectKind::RockerFoot || c.effect.kind == EffectKind::FootOffset));
    // Of the order of roll-over-shape radii (0.3 × leg length, leg 0.98 m; docs/commands/import-opensim.md: ≈ 0.5).
    CHECK(dg.extended_robot.foot_radius > 0.2);
    CHECK(dg.extended_robot.foot_radius < 0.75);
    // The foot moment is measured (the α row); the rolling foot is checked by the CoP travel,
    // which a rocker explains on the other leg's stances as in the import's own CoP fit.
    CHECK(dg.rms_reduction_pct[kCopX] > 50.0);
    CHECK_THAT(diagnosisReport(dg), Contains("the point foot is the cause"));
  }
}
