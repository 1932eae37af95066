// `gaitopt evaluate`: summary.json and trajectory.csv of the shipped step (and fewer rows at a
// lower --sample-rate), bad input exiting 2 with nothing written, an undefined step exiting 3
// without a trajectory.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/io/trajectory_file.hpp"
#include "test_files.hpp"
#include "test_gait_document.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using namespace gaitopt::test;  // runCli, quoted, readFile, sourcePath, ScratchDir, gaitWith

namespace {

const std::string kExample = sourcePath("configs/gait/default_step.yaml");

// Scratch directory for gait files and command outputs, removed when the test binary exits.
ScratchDir& scratch() {
  static ScratchDir dir("evaluate", "gait");
  return dir;
}

}  // namespace

TEST_CASE("gaitopt evaluate writes summary.json and trajectory.csv", "[gait_io]") {
  const std::string out = scratch().fresh("out_ok") + "/nested";
  const CliRun run = runCli("evaluate --gait " + quoted(kExample) + " --out " + quoted(out));
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  // The one vocabulary of optimize and sweep: feasible / infeasible / undefined.
  CHECK_THAT(run.out, StartsWith("evaluate: feasible, C_Gamma ") &&
                          Contains("largest violation at the nodes 0, between them (10x) "));
  CHECK(std::count(run.out.begin(), run.out.end(), '\n') == 1);

  const std::string summary = readFile(out + "/summary.json");
  CHECK_THAT(summary, Contains("\"status\": \"ok\""));
  // The shipped step (the default optimum, with dry friction) holds at the grid nodes and
  // between them: the one verdict says so.
  CHECK_THAT(summary, Contains("\"feasible\": true"));
  CHECK_THAT(summary, Contains("\"failed_level\": null"));
  CHECK_THAT(summary, Contains("\"unmet_constraints\": []"));
  CHECK_THAT(summary, Contains("\"worst_constraint\": \""));
  CHECK_THAT(summary, Contains("\"C_Gamma\": "));
  CHECK_THAT(summary, Contains("\"name\": \"torque_envelope_ss\""));
  CHECK_THAT(summary, Contains("\"max_violation\": "));

  const std::string csv = readFile(out + "/trajectory.csv");
  const std::string header = gaitopt::trajectoryCsv({});
  REQUIRE(csv.compare(0, header.size(), header) == 0);
  const auto rows = std::count(csv.begin(), csv.end(), '\n') - 1;
  CHECK(rows >= 100);
  CHECK(csv.find("nan") == std::string::npos);

  // --sample-rate overrides options.sample_rate: fewer rows at 100 Hz than at 1000 Hz.
  const std::string out2 = scratch().fresh("out_rate");
  const CliRun slow = runCli("evaluate --gait " + quoted(kExample) + " --out " + quoted(out2) +
                             " --sample-rate 100");
  REQUIRE(slow.exit_code == 0);
  const std::string csv2 = readFile(out2 + "/trajectory.csv");
  const auto rows2 = std::count(csv2.begin(), csv2.end(), '\n') - 1;
  CHECK(rows2 < rows / 5);
  CHECK(rows2 >= 10);
}

TEST_CASE("gaitopt evaluate rejects bad input without writing anything", "[gait_io]") {
  const std::string gait = scratch().write(gaitWith({{24, "  ss_nodes: 32.5"}}));
  const std::string out = scratch().fresh("out_bad");
  const CliRun run = runCli("evaluate --gait " + quoted(gait) + " --out " + quoted(out));
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Contains(gait + ":24: key 'options.ss_nodes': "));
  CHECK_FALSE(fs::exists(out));

  const CliRun rate = runCli("evaluate --gait " + quoted(kExample) + " --out " + quoted(out) +
                             " --sample-rate -5");
  CHECK(rate.exit_code == 2);
  CHECK_FALSE(fs::exists(out));

  const CliRun missing = runCli("evaluate --gait " + quoted(out + ".yaml") + " --out " +
                                quoted(out));
  CHECK(missing.exit_code == 2);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("gaitopt evaluate reports an undefined step with exit code 3", "[gait_io]") {
  // d = 2 m: the rear leg cannot reach the ground, level 0 fails.
  const std::string gait = scratch().write(gaitWith({{7, "  d: 2.0"}}));
  const std::string out = scratch().fresh("out_undefined");
  fs::create_directories(out);
  std::ofstream(out + "/trajectory.csv") << "stale\n";  // from an earlier run
  const CliRun run = runCli("evaluate --gait " + quoted(gait) + " --out " + quoted(out));
  INFO(run.err);
  CHECK(run.exit_code == 3);
  CHECK_THAT(run.out, Contains("undefined"));
  const std::string summary = readFile(out + "/summary.json");
  CHECK_THAT(summary, Contains("\"status\": \"undefined\""));
  CHECK_THAT(summary, Contains("\"failed_level\": 0"));
  CHECK_THAT(summary, Contains("\"criteria\": null"));
  CHECK_THAT(summary, Contains("\"T_SS\": null"));
  std::string lower = summary;
  std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
  CHECK(lower.find("nan") == std::string::npos);
  CHECK(lower.find("inf") == std::string::npos);
  CHECK_FALSE(fs::exists(out + "/trajectory.csv"));
}
