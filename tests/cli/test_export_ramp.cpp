// `gaitopt export --ramp`: the default gait's ramp from rest to rest written, a gait whose path
// cannot start from rest reported with exit 3, a bad ramp option with exit 2.
#include <catch2/catch.hpp>

#include <filesystem>

#include "gaitopt/export/controller_export.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

TEST_CASE("gaitopt export --ramp: the default gait exits 0, a gait that cannot start exits 3",
          "[export][ramp]") {
  ScratchDir dir("ramp");
  const std::string out = dir.fresh("walk") + ".csv";
  const std::string gait = sourcePath("configs/gait/default_step.yaml");
  CliRun run = runCli("export --gait " + quoted(gait) + " --steps 4 --rate 1000 --ramp --out " +
                      quoted(out));
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  const ExportCsvFile back = readExportCsv(out);
  CHECK(back.rows.front().alphad == 0.0);
  CHECK(back.rows.front().phid.lpNorm<Eigen::Infinity>() == 0.0);
  CHECK(back.rows.back().step == 8);  // standing start, 2 + 4 + 2 steps
  // Chessé's 0.85 m/s gait: its first SS needs alphad_iSS = -2.94 rad/s, which no standing
  // start reaches within the constraints (the message names the row the best design misses).
  const std::string chesse = dir.fresh("chesse") + ".csv";
  run = runCli("export --gait " + quoted(sourcePath("configs/gait/chesse_0.85_ipopt.yaml")) +
               " --steps 2 --rate 250 --ramp --out " + quoted(chesse));
  CHECK(run.exit_code == 3);
  CHECK_THAT(run.err, Catch::Matchers::Contains("no start from rest"));
  CHECK_THAT(run.err, Catch::Matchers::Contains("still violated by"));
  CHECK_FALSE(std::filesystem::exists(chesse));
  const CliRun bad =
      runCli("export --gait " + quoted(gait) + " --ramp --ramp-steps 1 --out " + quoted(out));
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::Matchers::Contains("--ramp-steps"));
}

}  // namespace gaitopt::test
