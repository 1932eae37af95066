// `gaitopt export-model`: the MJCF and URDF files written are the library's documents; a bad
// format exits 2.
#include <catch2/catch.hpp>

#include "gaitopt/export/robot_export.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

TEST_CASE("gaitopt export-model CLI writes MJCF and URDF, rejects a bad format",
          "[export]") {
  ScratchDir dir("export_model");
  const std::string robot = sourcePath("configs/robot/rabbit_miossec.yaml");
  const std::string mjcf = dir.fresh("robot") + ".xml";
  CliRun run = runCli("export-model --robot " + quoted(robot) + " --format mjcf --out " +
                      quoted(mjcf));
  REQUIRE(run.exit_code == 0);
  CHECK(readFile(mjcf) == robotMjcf(loadRobot(robot)));
  const std::string urdf = dir.fresh("robot") + ".urdf";
  run = runCli("export-model --robot " + quoted(robot) + " --format urdf --out " + quoted(urdf));
  REQUIRE(run.exit_code == 0);
  CHECK(readFile(urdf) == robotUrdf(loadRobot(robot)));
  run = runCli("export-model --robot " + quoted(robot) + " --format sdf --out " +
               quoted(dir.fresh("x")));
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Matchers::Contains("--format"));
}

}  // namespace gaitopt::test
