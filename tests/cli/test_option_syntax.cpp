// Option syntax (docs/reliability.md): every numeric option is a decimal number in range (no
// nan, inf, hex, empty `--opt=`, negative seed); messages quote at most 200 bytes of a value;
// input files that are not regular files are named as such, a FIFO without blocking.
#include <catch2/catch.hpp>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "test_files.hpp"
#include "test_opensim_data.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace gaitopt::test;

namespace {

ScratchDir& scratch() {
  static ScratchDir dir("option_syntax", "input");
  return dir;
}

}  // namespace

TEST_CASE("option syntax: numbers are decimal, finite and in range", "[reliability][cli]") {
  const std::string gait = quoted(sourcePath("configs/gait/default_step.yaml"));
  const std::string robot = quoted(sourcePath("configs/robot/rabbit_miossec.yaml"));
  const std::string out = scratch().fresh("out");
  const std::string model = "export-model --format mjcf --robot " + robot + " --out " +
                            quoted(out) + " ";
  const std::string exporter = "export --gait " + gait + " --out " + quoted(out) + " ";
  const std::string synth = "synth --robot " + robot + " --gait " + gait + " --out " +
                            quoted(out) + " --steps 3 ";
  const std::string opensim = "import-opensim --ik " + quoted(opensimIk()) + " --grf " +
                              quoted(opensimGrf()) + " --out " + quoted(out) + " ";
  // A double-support configuration with foot 2 on the ground (test::walkingImpactQ).
  const std::string map = "impact-map --robot " + robot + " --out " + quoted(out) +
                          " --q=-0.4,-2.8415926535897933,-3.3415926535897933,"
                          "0.50741499796637735,-2.7987334866164235 ";
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {model + "--timestep nan", "--timestep: not a finite number: 'nan'"},
      {model + "--timestep 0x1p-10", "--timestep: not a decimal number: '0x1p-10'"},
      {model + "--foot-radius=-inf", "not a finite number: '-inf'"},
      {model + "--ground-friction 11", "must be in [0, 10], got 11"},
      {model + "--timestep=", "--timestep=: empty value after '='"},
      {exporter + "--steps 0x10", "--steps: '0x10' is not a whole decimal number"},
      {exporter + "--steps 1e1", "'1e1' is not a whole decimal number"},
      {exporter + "--steps= 7", "--steps=: empty value after '='"},
      {exporter + "--rate nan", "--rate: not a finite number: 'nan'"},
      {exporter + "--rate 0", "must be in (0, 100000] Hz, got 0"},
      {synth + "--seed -1", "--seed: must be in [0, 9007199254740991], got -1"},
      {synth + "--seed 18446744073709551615", "is not a whole decimal number"},
      {"simulate --gait " + gait + " --out " + quoted(out) + " --sample-rate nan",
       "--sample-rate: not a finite number: 'nan'"},
      {"stability --gait " + gait + " --out " + quoted(out) + " --fd-step nan",
       "--fd-step: not a finite number: 'nan'"},
      {opensim + "--cutoff nan", "--cutoff: not a finite number: 'nan'"},
      {opensim + "--cutoff 0", "--cutoff: must be in (0, 1000] Hz, got 0"},
      {opensim + "--belt-speed inf", "--belt-speed: not a finite number: 'inf'"},
      {"simulate --gait " + gait + " --out " + quoted(out) + " --perturb alphad=nan",
       "--perturb: expected KIND=VALUE (a decimal VALUE), got 'alphad=nan'"},
      {synth + "--effect coulomb@knee_left=0x10",
       "--effect: 'coulomb@knee_left=0x10': not a decimal number: '0x10'"},
      // Ranges that bound a run's time and memory (docs/reliability.md).
      {synth + "--steps 301", "--steps: must be in [3, 300], got 301"},
      // Effect values: beyond what synth generates (10 × diagnose's admissible ranges).
      {synth + "--effect coulomb@knee_left=1e30",
       "--effect: 'coulomb@knee_left=1e30': outside the range synth generates on the robot, "
       "[-5.48, 140] N·m: the admissible range (-5.48, 14) stretched 10 times"},
      {synth + "--effect torque_offset@hip_right=-57", "[-56, 56] N·m"},
      {synth + "--unmodelled joint_compliance@knee_left=100",
       "--unmodelled: 'joint_compliance@knee_left=100': outside the range synth generates on "
       "the robot, [140, inf] N·m/rad: the peak envelope torque (140 N·m) twists the joint"},
      {synth + "--unmodelled knee_centre@knee_right=0.5", "[0, 0.4] m/rad"},
      {exporter + "--steps 100000 --rate 100000",
       "--steps, --rate: 100000 steps of 0.6"},
      {exporter + "--steps 400 --rate 1000", "rows, more than the limit of 200000"},
      {"simulate --gait " + gait + " --out " + quoted(out) + " --steps 10000 --sample-rate 1e5",
       "--steps, --sample-rate: 10000 steps of"},
      {map + "--mu-range 0:1:100000", "integer 1 <= n <= 10000"},
      {map + "--mu-range 0:1:10000 --theta-range=-180:0:101",
       "--mu-range, --theta-range: 10000 x 101 points, more than the limit of 1000000"},
  };
  for (const Case& c : cases) {
    const CliRun run = runCli(c.args);
    INFO(c.args << "\n" << run.err);
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.err, Contains(c.message));
    CHECK_FALSE(fs::exists(out));
  }
  // A long value is quoted by its first 200 bytes, whatever reports it.
  const std::string x(5000, 'x');
  for (const std::string& args : {model + "--timestep " + x, model + "--format " + x,
                                  "export-model --format mjcf --robot " + x + " --out o.xml"}) {
    const CliRun run = runCli(args);
    INFO(run.err.substr(0, 400));
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.err, Contains(std::string(200, 'x') + "..."));
    CHECK(run.err.find(std::string(201, 'x')) == std::string::npos);
  }
}

TEST_CASE("option syntax: diagnose refuses torques far beyond the robot's envelope",
          "[reliability][cli]") {
  std::string csv = readFile(sourcePath("fuzz/seeds/measured.csv"));
  csv.replace(csv.find("\n0,-0.2,-2.8,-3.4,0,-2.9,SS,left,0,0,"), 37,
              "\n0,-0.2,-2.8,-3.4,0,-2.9,SS,left,0,1e30,");
  const std::string data = scratch().fresh("huge") + ".csv";
  std::ofstream(data) << csv;
  const std::string out = scratch().fresh("out");
  const CliRun run = runCli("diagnose --robot " +
                            quoted(sourcePath("configs/robot/rabbit_miossec.yaml")) + " --data " +
                            quoted(data) + " --out " + quoted(out));
  INFO(run.err);
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Contains(data + ": column 'gamma1', sample 1 (t = 0 s): 1e+30 N m is beyond "
                                      "10 times the robot's largest envelope torque (140 N m)"));
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("option syntax: inputs are regular files, a FIFO does not block", "[reliability][cli]") {
  const std::string fifo = scratch().fresh("fifo");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const std::string folder = scratch().fresh("folder");
  fs::create_directories(folder);
  const std::string robot = quoted(sourcePath("configs/robot/rabbit_miossec.yaml"));
  const std::string out = scratch().fresh("out");
  const std::string diagnose = "diagnose --robot " + robot + " --out " + quoted(out) + " --data ";
  const std::string opensim = "import-opensim --grf " + quoted(opensimGrf()) + " --out " +
                              quoted(out) + " --ik ";
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {diagnose + quoted(fifo), "is a FIFO (named pipe), a regular file is expected"},
           {diagnose + quoted(folder), "is a directory, a file is expected"},
           {diagnose + "/dev/null", "/dev/null: is a device, a regular file is expected"},
           {opensim + quoted(fifo), "is a FIFO (named pipe)"},
           {"export-model --format mjcf --out " + quoted(out) + " --robot " + quoted(fifo),
            "is a FIFO (named pipe)"}}) {
    // Run under a time limit so that a regression fails instead of hanging the suite.
    const CliRun run = runCli("--version >/dev/null; timeout 60 " + quoted(GAITOPT_CLI) + " " + args);
    INFO(args << "\n" << run.err);
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.err, Contains(message));
    CHECK_FALSE(fs::exists(out));
  }
}
