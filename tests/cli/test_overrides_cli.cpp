// --set, --speed and --robot on the command line: applied, recorded in the outputs, and a bad
// override refused before anything is written.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "test_files.hpp"
#include "test_support.hpp"

using namespace gaitopt;
using Catch::Matchers::Contains;
using test::runCli;

TEST_CASE("gaitopt evaluate --speed --set: applied and recorded in summary.json", "[overrides]") {
  test::ScratchDir dir("overrides_cli");
  const std::string out = dir.fresh("eval");
  const test::CliRun run = runCli(
      "evaluate --gait " + test::quoted(test::sourcePath("configs/gait/default_step.yaml")) +
      " --speed 0.45 --set options.sample_rate=200 --out " + test::quoted(out));
  REQUIRE(run.exit_code == 0);
  const std::string summary = test::readFile(out + "/summary.json");
  CHECK_THAT(summary, Contains("\"overrides\": [\"options.target_speed=0.45\", "
                               "\"options.sample_rate=200\"]"));
  CHECK_THAT(summary, Contains("\"target_speed\": 0.45"));
  // 200 Hz: the trajectory has about T · 200 rows instead of T · 1000.
  const std::string csv = test::readFile(out + "/trajectory.csv");
  const long rows = std::count(csv.begin(), csv.end(), '\n');
  CHECK(rows > 50);
  CHECK(rows < 200);
}

TEST_CASE("gaitopt optimize: a bad --set exits 2 naming it, nothing written", "[overrides]") {
  test::ScratchDir dir("overrides_cli");
  const std::string out = dir.fresh("opt");
  const std::string config = test::quoted(test::sourcePath("configs/default.yaml"));
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"--set options.friction_coefficient=-1",
            "--set options.friction_coefficient=-1: key 'options.friction_coefficient'"},
           {"--set solver.max_iter=x", "--set solver.max_iter=x: key 'solver.max_iter'"},
           {"--set speed", "--set: expected KEY=VALUE"},
           {"--speed nan", "--speed"},
           {"--robot /nonexistent.yaml", "--robot"}}) {
    const test::CliRun run = runCli("optimize --config " + config + " " + args + " --out " +
                                    test::quoted(out));
    INFO(args << "\n" << run.err);
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.err, Contains(message));
    CHECK_FALSE(std::filesystem::exists(out));
  }
}

TEST_CASE("gaitopt export --robot --set: the embedded gait is the one exported", "[overrides]") {
  test::ScratchDir dir("overrides_cli");
  const std::string out = dir.fresh("walk") + ".json";
  const test::CliRun run = runCli(
      "export --gait " + test::quoted(test::sourcePath("configs/gait/default_step.yaml")) +
      " --set options.friction_coefficient=0.55 --format json --steps 1 --rate 200 --out " +
      test::quoted(out));
  REQUIRE(run.exit_code == 0);
  const std::string json = test::readFile(out);
  CHECK_THAT(json, Contains("\"overrides\": \"options.friction_coefficient=0.55\""));
  CHECK_THAT(json, Contains("with the overrides of metadata.overrides"));
  CHECK_THAT(json, Contains("friction_coefficient: 0.55"));
  // A library is a sweep's gaits as optimised: nothing to override.
  const test::CliRun library = runCli("export --library " + test::quoted(dir.dir().string()) +
                                      " --set options.ss_nodes=24 --format json --out " +
                                      test::quoted(dir.fresh("lib") + ".json"));
  CHECK(library.exit_code == 2);
  CHECK_THAT(library.err, Contains("--robot, --set: override the --gait file, not a --library"));
}

TEST_CASE("a run folder with the figures of its result is replaced by a re-run", "[rerun]") {
  test::ScratchDir dir("rerun");
  const std::string out = dir.fresh("run");
  const std::string eval = "evaluate --gait " +
                           test::quoted(test::sourcePath("configs/gait/default_step.yaml")) +
                           " --out " + test::quoted(out);
  REQUIRE(runCli(eval).exit_code == 0);
  // `gaitopt plot stick|torques OUT` leaves OUT/stick.png, OUT/torques.png: a re-run replaces
  // the result and its figures go with it.
  std::ofstream(out + "/stick.png") << "figure";
  std::ofstream(out + "/torques.png") << "figure";
  const test::CliRun again = runCli(eval);
  CHECK(again.exit_code == 0);
  CHECK(std::filesystem::exists(out + "/summary.json"));
  CHECK_FALSE(std::filesystem::exists(out + "/stick.png"));
  CHECK_FALSE(std::filesystem::exists(out + "/torques.png"));
  // A file that no gaitopt command writes there is the user's: the folder is refused.
  for (const std::string name : {"notes.txt", "photo.png", "stick.svg"}) {
    std::ofstream(out + "/" + name) << "user's";
    const test::CliRun refused = runCli(eval);
    INFO(name);
    CHECK(refused.exit_code == 2);
    CHECK_THAT(refused.err, Contains("holds '" + name + "', which gaitopt did not write"));
    std::filesystem::remove(out + "/" + name);
  }
}
