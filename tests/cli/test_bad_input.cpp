// The bad-input table of docs/reliability.md: for each class of bad or hostile
// input, the exit code, the message (file, key and line, or the option) and that nothing was
// written or overwritten; safe writing (planted links, interrupted re-runs, --out checks).
#include <catch2/catch.hpp>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/io/sweep_file.hpp"
#include "gaitopt/io/yaml_reader.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace gaitopt::test;  // CliRun, runCli, quoted, readFile, sourcePath, ScratchDir

namespace {

ScratchDir& scratch() {
  static ScratchDir dir("bad_input", "input");
  return dir;
}

const std::string kConfig = sourcePath("configs/default.yaml");
const std::string kGait = sourcePath("configs/gait/default_step.yaml");
const std::string kRobot = sourcePath("configs/robot/rabbit_miossec.yaml");

// A file that must survive every run untouched.
std::string victim() {
  const std::string path = scratch().fresh("victim");
  std::ofstream(path) << "precious\n";
  return path;
}

// Names in `dir`, hidden ones included.
std::set<std::string> entries(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

// A bad-input run: exit 2, the message contains `expected`, nothing on standard output.
void requireBadInput(const std::string& args, const std::string& expected) {
  const CliRun run = runCli(args);
  INFO(args << "\n" << run.out << run.err);
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Contains(expected));
  CHECK(run.out.empty());
}

// `text` as an optimiser configuration using the shipped robot.
std::string config(const std::string& text) {
  return scratch().write("robot: " + kRobot + "\n" + text);
}

}  // namespace

TEST_CASE("bad input: outputs never follow a planted link", "[reliability]") {
  const std::string precious = victim();
  // Library level: the final name is a link to the victim; the link is replaced, not followed.
  const fs::path dir = scratch().fresh("links");
  fs::create_directories(dir);
  fs::create_symlink(precious, dir / "summary.json");
  gaitopt::writeFileAtomically((dir / "summary.json").string(), "new\n");
  CHECK(readFile(precious) == "precious\n");
  CHECK_FALSE(fs::is_symlink(dir / "summary.json"));
  CHECK(readFile((dir / "summary.json").string()) == "new\n");
  CHECK(entries(dir) == std::set<std::string>{"summary.json"});  // no temporary left

  // CLI: links at the output names in --out are replaced with the run's files.
  const fs::path out = scratch().fresh("out_links");
  fs::create_directories(out);
  fs::create_symlink(precious, out / "summary.json");
  fs::create_symlink(precious, out / "trajectory.csv");
  const CliRun ok = runCli("evaluate --gait " + quoted(kGait) + " --out " + quoted(out.string()));
  CHECK(ok.exit_code == 0);
  CHECK(readFile(precious) == "precious\n");
  CHECK_FALSE(fs::is_symlink(out / "summary.json"));
  CHECK_THAT(readFile((out / "summary.json").string()), Contains("\"C_Gamma\""));

  // A planted summary.json.tmp is not gaitopt's, so --out is refused.
  const fs::path planted = scratch().fresh("out_planted");
  fs::create_directories(planted);
  fs::create_symlink(precious, planted / "summary.json.tmp");
  requireBadInput("evaluate --gait " + quoted(kGait) + " --out " + quoted(planted.string()),
                  "holds 'summary.json.tmp', which gaitopt did not write");
  CHECK(readFile(precious) == "precious\n");
  CHECK(entries(planted) == std::set<std::string>{"summary.json.tmp"});
}

TEST_CASE("bad input: a configuration cannot write outside --out", "[reliability]") {
  const std::string precious = victim();
  const std::string out = scratch().fresh("out_ipopt");
  const std::string absolute =
      config("solver: {backend: ipopt, ipopt: {output_file: " + precious + "}}\n");
  requireBadInput("optimize --config " + quoted(absolute) + " --out " + quoted(out),
                  absolute + ":2: key 'solver.ipopt.output_file': must be a plain file name");
  CHECK(readFile(precious) == "precious\n");
  CHECK_FALSE(fs::exists(out));
  requireConfigError(
      gaitopt::loadOptimizeConfig,
      config("solver: {backend: ipopt, ipopt: {output_file: ../ipopt.out}}\n"),
      "solver.ipopt.output_file", 2, "plain file name");
  requireConfigError(
      gaitopt::loadOptimizeConfig,
      config("solver: {backend: ipopt, ipopt: {option_file_name: /etc/passwd}}\n"),
      "solver.ipopt.option_file_name", 2, "not allowed");
  // A plain name is placed inside the run's directory.
  gaitopt::OptimizeConfig c = gaitopt::loadOptimizeConfig(
      config("solver: {backend: ipopt, ipopt: {output_file: ipopt.out}}\n"));
  gaitopt::placeIpoptOutputFile(c.solver, "/runs/a");
  CHECK(c.solver.ipopt_options.back().second == "/runs/a/ipopt.out");
}

TEST_CASE("bad input: Ipopt options are checked at load", "[reliability]") {
  const std::string out = scratch().fresh("out_solver");
  const std::string ma57 = config("solver:\n  backend: ipopt\n  ipopt: {linear_solver: ma57}\n");
  requireBadInput("optimize --config " + quoted(ma57) + " --out " + quoted(out),
                  ma57 + ":4: key 'solver.ipopt.linear_solver': linear solver 'ma57' is not "
                         "available");
  CHECK_FALSE(fs::exists(out));
  CHECK_NOTHROW(gaitopt::loadOptimizeConfig(
      config("solver: {backend: ipopt, ipopt: {linear_solver: mumps}}\n")));
  const std::string nlopt = config("solver:\n  backend: nlopt_cobyla\n  ipopt: {max_iter: 3}\n");
  requireBadInput("optimize --config " + quoted(nlopt) + " --out " + quoted(out),
                  nlopt + ":4: key 'solver.ipopt': Ipopt options are used only with backend: "
                          "ipopt (this run uses nlopt_cobyla)");
}

TEST_CASE("bad input: --out is checked before any work", "[reliability]") {
  const std::string file = victim();
  const std::string run = "optimize --config " + quoted(kConfig) + " --out ";
  requireBadInput(run + "''", "--out: empty directory name");
  requireBadInput(run + quoted(file), "exists and is not a directory");
  requireBadInput(run + quoted(file + "/sub"), "cannot create its parent");
  requireBadInput(run + quoted(scratch().fresh(std::string(256, 'n'))), "longer than 255 bytes");
  requireBadInput(run + "/proc/gaitopt_out", "cannot be written");
  requireBadInput(run + ".", "is the current directory or contains it");
  const fs::path foreign = scratch().fresh("out_foreign");
  fs::create_directories(foreign);
  std::ofstream(foreign / "notes.txt") << "mine\n";
  requireBadInput(run + quoted(foreign.string()), "holds 'notes.txt'");
  CHECK(readFile((foreign / "notes.txt").string()) == "mine\n");
  CHECK(readFile(file) == "precious\n");
}

TEST_CASE("bad input: an interrupted re-run leaves the previous result complete",
          "[reliability]") {
  const fs::path out = scratch().fresh("out_sweep");
  const std::string sweep = "sweep --config " + quoted(kConfig) + " --quiet --out " +
                            quoted(out.string()) + " --speeds ";
  REQUIRE(runCli(sweep + "0.5:0.6:0.1").exit_code == 0);
  const std::string csv = readFile((out / "sweep.csv").string());
  const std::string summary = readFile((out / "v0.500/summary.json").string());
  const std::set<std::string> before = entries(out.parent_path());
  for (const char* signal : {"TERM", "INT"}) {
    // A longer sweep into the same directory, stopped after 0.3 s (it needs about 1.5 s).
    const CliRun stopped = runCli("--version >/dev/null; timeout -s " + std::string(signal) +
                                  " 0.3 " + quoted(GAITOPT_CLI) + " " + sweep + "0.2:1.0:0.1");
    CHECK(stopped.exit_code == 124);  // timeout's code for a run it stopped
    CHECK(readFile((out / "sweep.csv").string()) == csv);
    CHECK(readFile((out / "v0.500/summary.json").string()) == summary);
    CHECK(entries(out) == std::set<std::string>{"sweep.csv", "v0.500", "v0.600"});
    CHECK(entries(out.parent_path()) == before);  // no temporary sibling left
  }
  // A completed re-run replaces the whole directory: no folder of the old run remains.
  REQUIRE(runCli(sweep + "0.5:0.5:0.1").exit_code == 0);
  CHECK(entries(out) == std::set<std::string>{"sweep.csv", "v0.500"});
}

TEST_CASE("bad input: command-line vectors and values", "[reliability]") {
  for (const char* q : {"nan,0,0,0,0", "0,inf,0,0,0", "0,0,1e300,0,0", "0,0,0,0,0x1p3"}) {
    requireBadInput(std::string("model --q ") + q, "--q: ");
  }
  requireBadInput("model --q 0,0,0,0,0 --qd 0,nan,0,0,0", "--qd: not a finite number: 'nan'");
  requireBadInput("model --q 0,0,0,0,0 --qdd 0,0,0,0,-inf", "--qdd: ");
  requireBadInput("model --q 0,0,0,0,0 --qd 0,0,0,0,2e3",
                  "must be in [-1000, 1000] rad/s, got 2e3");
  requireBadInput("frobnicate", "unknown subcommand 'frobnicate' (expected one of: model,");
  const std::string out = scratch().fresh("out_cli");
  const std::string sweep = "sweep --config " + quoted(kConfig) + " --out " + quoted(out);
  requireBadInput(sweep + " --speeds 1e300:1e300:1", "stop must be <= 10 m/s");
  requireBadInput(sweep + " --speeds 0.2:1:0.1 --shard 0/1000000",
                  "count 1000000 exceeds 10000, the largest number of speeds");
  requireBadInput(sweep + " --speeds 0.2:0.2:0.1,0.3", "'0.1,0.3' is not a finite number");
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("bad input: YAML documents, control characters, numbers as written",
          "[reliability]") {
  const auto load = gaitopt::loadOptimizeConfig;
  const auto fileError = [&](const std::string& path, int line, const std::string& problem) {
    try {
      load(path);
      FAIL("no ConfigError");
    } catch (const gaitopt::ConfigError& e) {
      CHECK(e.line() == line);
      CHECK_THAT(std::string(e.what()), Contains(problem));
      CHECK(std::string(e.what()).find('\x1b') == std::string::npos);
    }
  };
  fileError(config("speed: 0.5\n---\nspeed: 0.7\n"), 3, "a second YAML document");
  fileError(config("speed: 0.5 \x1b[2J\n"), 2, "control character \\x1b: not a text file");
  requireConfigError(load, config("speed: 0.20000000000000001e2\n"), "speed", 2,
                     "got 0.20000000000000001e2");
  requireConfigError(load, config("criterion: \"C_\xff\"\n"), "criterion", 2, "'C_\\xff'");
  // The CLI's own message is printable too.
  const CliRun run = runCli("optimize --config " + quoted(config("speed: \"\x07\"\n")) +
                            " --out " + quoted(scratch().fresh("out_bell")));
  CHECK(run.exit_code == 2);
  CHECK(run.err.find('\x07') == std::string::npos);
}

TEST_CASE("bad input: sweep-merge reads strictly typed rows", "[reliability]") {
  const std::string header = std::string(gaitopt::kSweepCsvHeader) + "\n";
  const std::string good = "0.5,optimal,9122.6,180.1,130.2,60.3,0.422,0.309,0.58,0.042,118,0.27,,,,,";
  const auto merge = [&](const std::string& row) {
    return gaitopt::mergeSweepCsvs({header + row + "\r\n"}, {"s/sweep.csv"});
  };
  CHECK(merge(good) == header + good + "\n");  // CRLF accepted
  CHECK(gaitopt::mergeSweepCsvs({header + good}, {"s"}) == header + good + "\n");  // no final \n
  const auto bad = [&](const std::string& row, const std::string& problem) {
    CHECK_THROWS_WITH(merge(row), Contains("s/sweep.csv:2: column " + problem));
  };
  bad("0.5,optimal,abc,180.1,130.2,60.3,0.422,0.309,0.58,0.042,118,0.27,,,,,", "C_Gamma: 'abc'");
  bad("0.5,happy,9122.6,180.1,130.2,60.3,0.422,0.309,0.58,0.042,118,0.27,,,,,", "status: 'happy'");
  bad("-0.5,optimal,9122.6,180.1,130.2,60.3,0.422,0.309,0.58,0.042,118,0.27,,,,,", "speed: '-0.5'");
  bad("0.5,optimal,9122.6,180.1,130.2,60.3,0.422,0.309,-0.58,0.042,118,0.27,,,,,", "T_SS: '-0.58'");
  bad("0.5,optimal,9122.6,180.1,130.2,60.3,0.422,0.309,0.58,0.042,1.5,0.27,,,,,", "iterations: '1.5'");
  bad("0.5,optimal,inf,180.1,130.2,60.3,0.422,0.309,0.58,0.042,118,0.27,,,,,", "C_Gamma: 'inf'");

  // The CLI: exit 2, nothing written; a sweep.csv that is a directory is named as such.
  const fs::path shard = scratch().fresh("shard");
  fs::create_directories(shard);
  std::ofstream(shard / "sweep.csv") << header << "0.5,happy,1,1,1,1,0.002,0.3,0.5,0.1,10,0.1,,,,,\n";
  const fs::path odd = scratch().fresh("shard_dir");
  fs::create_directories(odd / "sweep.csv");
  const std::string out = scratch().fresh("out_merge");
  requireBadInput("sweep-merge --out " + quoted(out) + " " + quoted(shard.string()),
                  "column status: 'happy' is not a status");
  requireBadInput("sweep-merge --out " + quoted(out) + " " + quoted(odd.string()),
                  "is missing or not a regular file");
  CHECK_FALSE(fs::exists(out));
}
