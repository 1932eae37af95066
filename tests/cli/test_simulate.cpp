// `gaitopt simulate`: outputs and outcome of the default gait, a plant without the support bar
// and the impact-landing gait (exit 3 when the walk fails), bad options exiting 2.
#include <catch2/catch.hpp>

#include "gaitopt/export/controller_export.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

TEST_CASE("gaitopt simulate CLI: outputs, outcome, bad input", "[sim]") {
  ScratchDir dir("simulate");
  const std::string gait = sourcePath("configs/gait/default_step.yaml");
  const std::string out = dir.fresh("walk");
  CliRun run = runCli("simulate --gait " + quoted(gait) +
                      " --steps 3 --perturb alphad=0.01 --out " + quoted(out));
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  std::string summary = readFile(out + "/summary.json");
  CHECK_THAT(summary, Catch::Matchers::Contains("\"outcome\": \"completed\""));
  CHECK_THAT(summary, Catch::Matchers::Contains("\"converged_to_cycle\": true"));
  // The gait was optimised with the plant's Coulomb friction: its torques stay within the
  // envelope, the torque projection never acts, the reference is tracked.
  CHECK_THAT(summary, Catch::Matchers::Contains("\"tracks_reference\": true"));
  CHECK_THAT(summary, Catch::Matchers::Contains("\"impact_model\": \"double_support\""));
  run = runCli("simulate --gait " + quoted(gait) + " --steps 2 --no-torque-limits --out " +
               quoted(dir.fresh("walk")));
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(run.out, Catch::Matchers::Contains("tracks reference yes"));
  const ExportCsvFile traj = readExportCsv(out + "/trajectory.csv");
  CHECK(traj.rows.back().step == 2);
  CHECK(traj.rows.front().stance == Leg::Left);
  // A plant without the support bar: its foot lands by height with the held impact, then the
  // controller's DS force split (built with the bar) slips the rear foot at once.
  const std::string out2 = dir.fresh("walk");
  run = runCli("simulate --gait " + quoted(gait) + " --steps 2 --plant " +
               quoted(sourcePath("configs/robot/rabbit_miossec_nobar.yaml")) + " --out " +
               quoted(out2));
  CHECK(run.exit_code == 3);
  CHECK_THAT(readFile(out2 + "/summary.json"),
             Catch::Matchers::Contains("friction cone in double support, step 0"));
  CHECK_THAT(readFile(out2 + "/steps.csv"), Catch::Matchers::Contains(",held/stick,"));
  // The impact-landing gait: algebraic impact by default; a low-μ ground slides at impact.
  const std::string impact_gait = sourcePath("configs/gait/chevallereau_aoustin_0.75_impact.yaml");
  const std::string out3 = dir.fresh("walk");
  run = runCli("simulate --gait " + quoted(impact_gait) + " --steps 2 --out " + quoted(out3));
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(readFile(out3 + "/summary.json"),
             Catch::Matchers::Contains("\"impact_model\": \"algebraic\""));
  CHECK_THAT(readFile(out3 + "/steps.csv"), Catch::Matchers::Contains(",lift/stick,"));
  const std::string out4 = dir.fresh("walk");
  run = runCli("simulate --gait " + quoted(impact_gait) + " --steps 2 --ground-mu 0.5 --out " +
               quoted(out4));
  CHECK(run.exit_code == 3);
  CHECK_THAT(readFile(out4 + "/summary.json"),
             Catch::Matchers::Contains("\"outcome\": \"slipped\""));
  run = runCli("simulate --gait " + quoted(gait) + " --ds-control fastest --out " +
               quoted(dir.fresh("bad")));
  CHECK(run.exit_code == 2);
  run = runCli("simulate --gait " + quoted(gait) + " --perturb knee=1 --out " +
               quoted(dir.fresh("bad")));
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Matchers::Contains("unknown KIND 'knee'"));
  run = runCli("simulate --gait " + quoted(gait) + " --perturb slope=0.6 --out " +
               quoted(dir.fresh("bad")));
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Matchers::Contains("slope must be within (-0.5, 0.5) rad"));
  run = runCli("simulate --gait " + quoted(gait) + " --perturb alphad=1e30 --out " +
               quoted(dir.fresh("bad")));
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Matchers::Contains("alphad must be within [-5, 5] rad/s, got "
                                                "'alphad=1e30'"));
  run = runCli("simulate --gait " + quoted(gait) + " --perturb delta3=-0.7 --out " +
               quoted(dir.fresh("bad")));
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Matchers::Contains("delta3 must be within [-0.5, 0.5] rad"));
}

}  // namespace gaitopt::test
