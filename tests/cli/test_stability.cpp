// `gaitopt stability` on the default gait: the analysis files written, exit 0 for its stable
// cycle; a bad Jacobian method exits 2.
#include <catch2/catch.hpp>

#include <algorithm>

#include "test_files.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

TEST_CASE("gaitopt stability CLI writes the analysis and exits 0 for a stable cycle",
          "[sim][poincare]") {
  ScratchDir dir("stability");
  const std::string out = dir.fresh("stab");
  const CliRun run = runCli("stability --gait " +
                            quoted(sourcePath("configs/gait/default_step.yaml")) +
                            " --map-points 3 --map-range 0.01 --margin-steps 1 --out " +
                            quoted(out));
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  // A progress line as each of the six stages starts, before the result line.
  for (int k = 1; k <= 6; ++k)
    CHECK_THAT(run.out, Catch::Matchers::Contains("stability [" + std::to_string(k) + "/6] "));
  CHECK_THAT(run.out, Catch::Matchers::Contains("[6/6] margins: push, payload, slope  elapsed"));
  CHECK_THAT(readFile(out + "/stability.json"), Catch::Matchers::Contains("\"stable\": true"));
  const std::string map = readFile(out + "/zero_dynamics_map.csv");
  const std::string jac = readFile(out + "/jacobian.csv");
  CHECK(std::count(map.begin(), map.end(), '\n') == 4);
  CHECK(std::count(jac.begin(), jac.end(), '\n') == 11);
  CHECK_THAT(map, Catch::Matchers::StartsWith("alphad_iSS,alphad_iDS,next_alphad_iSS,"
                                              "next_alphad_iDS,steps_to_cycle,outcome\n"));
  const std::string json = readFile(out + "/stability.json");
  CHECK_THAT(json, Catch::Matchers::Contains("\"jacobian_method\": \"sensitivity\""));
  CHECK_THAT(json, Catch::Matchers::Contains("\"zero_dynamics\""));
  CHECK_THAT(json, Catch::Matchers::Contains("\"push_forward\""));
  CHECK_THAT(json, Catch::Matchers::Contains("\"recovery_steps\": 1"));
  CHECK_THAT(json, Catch::Matchers::Contains("\"slope\": {"));
  CHECK_THAT(json, Catch::Matchers::Contains("\"down\": {"));
  const CliRun bad = runCli("stability --gait " +
                            quoted(sourcePath("configs/gait/default_step.yaml")) +
                            " --jacobian exact --out " + quoted(dir.fresh("bad")));
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::Matchers::Contains("--jacobian"));
}

}  // namespace gaitopt::test
