// `gaitopt sweep` and `gaitopt sweep-merge`: sweep.csv and one folder per speed, two shards
// merged into the full list, duplicates and bad input exiting 2 with nothing written.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "gaitopt/io/sweep_file.hpp"
#include "test_files.hpp"
#include "test_support.hpp"
#include "test_sweep_csv.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace gaitopt::test;  // runCli, quoted, readFile, ScratchDir, lines, firstField

namespace {

ScratchDir& scratch() {
  static ScratchDir s("sweep");
  return s;
}

const std::string kConfig = sourcePath("configs/default.yaml");

}  // namespace

TEST_CASE("gaitopt sweep and sweep-merge: outputs, shards, exit codes", "[sweep]") {
  REQUIRE(fs::exists(kConfig));
  const std::string cfg = quoted(kConfig);

  SECTION("one run writes sweep.csv and one folder per speed") {
    const std::string out = scratch().fresh("sweep");
    const CliRun r =
        runCli("sweep --config " + cfg + " --speeds 0.4:0.6:0.1 --out " + quoted(out));
    INFO(r.out << r.err);
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("[3/3] v="));
    const std::vector<std::string> csv = lines(readFile(out + "/sweep.csv"));
    REQUIRE(csv.size() == 4);
    CHECK(csv[0] ==
          "speed,status,C_Gamma,C_E,W,C_frott,CoT,step_length,T_SS,T_DS,iterations,wall_time_s,"
          "min_violation,blocking_constraint,blocking_value,blocking_unit,blocking_multiplier");
    for (std::size_t i = 1; i < csv.size(); ++i) CHECK_THAT(csv[i], Contains(",optimal,"));
    for (const char* v : {"v0.400", "v0.500", "v0.600"})
      for (const char* f : {"summary.json", "gait.yaml", "trajectory.csv"}) {
        INFO(v << "/" << f);
        CHECK(fs::exists(fs::path(out) / v / f));
      }
  }

  SECTION("two shards merge into the full list") {
    const std::string a = scratch().fresh("shard0"), b = scratch().fresh("shard1");
    const std::string merged = scratch().fresh("merged");
    const CliRun r0 = runCli("sweep --config " + cfg +
                             " --speeds 0.4:0.6:0.1 --shard 0/2 --quiet --out " + quoted(a));
    const CliRun r1 = runCli("sweep --config " + cfg +
                             " --speeds 0.4:0.6:0.1 --shard 1/2 --quiet --out " + quoted(b));
    INFO(r0.out << r0.err << r1.out << r1.err);
    CHECK(r0.exit_code == 0);
    CHECK(r1.exit_code == 0);
    CHECK(lines(readFile(a + "/sweep.csv")).size() == 2);
    CHECK(lines(readFile(b + "/sweep.csv")).size() == 3);
    const CliRun m =
        runCli("sweep-merge --out " + quoted(merged) + " " + quoted(b) + " " + quoted(a));
    INFO(m.out << m.err);
    CHECK(m.exit_code == 0);
    const std::vector<std::string> csv = lines(readFile(merged + "/sweep.csv"));
    REQUIRE(csv.size() == 4);
    CHECK(csv[0] == gaitopt::kSweepCsvHeader);
    CHECK(firstField(csv[1]) == 0.4);
    CHECK(firstField(csv[2]) == 0.5);
    CHECK(firstField(csv[3]) == 0.6);

    const std::string dup = scratch().fresh("dup");
    const CliRun d =
        runCli("sweep-merge --out " + quoted(dup) + " " + quoted(a) + " " + quoted(a));
    CHECK(d.exit_code == 2);
    CHECK_THAT(d.err, Contains("appears twice"));
    CHECK_FALSE(fs::exists(dup));
  }

  SECTION("bad input exits 2 and writes nothing") {
    for (const std::string bad :
         {"--speeds 0.6:0.4:0.1", "--speeds 0.4:0.6", "--speeds a:b:c",
          "--speeds 0.4:0.6:0.1 --shard 3/2", "--speeds 0.4:0.6:0.1 --shard 0/4",
          "--speeds 0.4:0.6:0.1 --jobs 0"}) {
      const std::string out = scratch().fresh("bad");
      const CliRun r = runCli("sweep --config " + cfg + " " + bad + " --out " + quoted(out));
      INFO(bad << ": " << r.err);
      CHECK(r.exit_code == 2);
      CHECK_FALSE(r.err.empty());
      CHECK_FALSE(fs::exists(out));
    }
    const std::string out = scratch().fresh("bad_config");
    const CliRun r =
        runCli("sweep --config " + quoted(out + ".yaml") + " --speeds 0.4:0.6:0.1 --out " +
               quoted(out));
    CHECK(r.exit_code == 2);
    CHECK_FALSE(fs::exists(out));
  }
}
