// `gaitopt optimize --global K --seed S`: the same seed gives the same summary.json (but the
// wall times).
#include <catch2/catch.hpp>

#include <regex>
#include <string>

#include "test_files.hpp"
#include "test_support.hpp"

namespace {

using Catch::Matchers::Contains;

const std::string kDefaultConfig = gaitopt::test::sourcePath("configs/default.yaml");

}  // namespace

TEST_CASE("global: the same seed gives the same output", "[optimize]") {
  gaitopt::test::ScratchDir scratch("global", "out");
  std::string blocks[2];
  for (std::string& block : blocks) {
    const std::string out = scratch.fresh("out_global");
    const gaitopt::test::CliRun run =
        gaitopt::test::runCli("optimize --config " + gaitopt::test::quoted(kDefaultConfig) +
                              " --out " + gaitopt::test::quoted(out) + " --global 1 --seed 1 --quiet");
    INFO(run.out << run.err);
    REQUIRE(run.exit_code == 0);
    CHECK_THAT(run.out, Contains("global: 1 of 1 optimised starts optimal") &&
                            Contains("1 clusters"));
    block = gaitopt::test::readFile(out + "/summary.json");
    CHECK_THAT(block, Contains("\"global\": {") && Contains("\"seed\": 1") &&
                          Contains("\"clusters\": [") && Contains("\"size\": 1") &&
                          Contains("\"median_time_per_start_s\": "));
    // Wall times differ from run to run; everything else must not.
    block = std::regex_replace(block, std::regex("\"(wall_time_s|median_time_per_start_s)\": [^,}\\n]*"), "");
  }
  CHECK(blocks[0] == blocks[1]);
}
