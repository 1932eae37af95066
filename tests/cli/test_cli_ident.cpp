// `gaitopt synth` and `gaitopt diagnose` end to end: files written, the extended robot file
// valid, shuffled columns giving the same diagnosis, bad input stopping with exit 2 and
// nothing written.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "gaitopt/io/robot_file.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

using namespace gaitopt;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

test::ScratchDir& scratch() {
  static test::ScratchDir dir("ident_cli", "x");
  return dir;
}

const std::string kRobot = test::quoted(test::sourcePath("configs/robot/rabbit_miossec.yaml"));
const std::string kGait = test::quoted(test::sourcePath("configs/gait/default_step.yaml"));

// The CSV with its columns in reverse order.
std::string reversedColumns(const std::string& csv) {
  std::istringstream in(csv);
  std::string line, out;
  while (std::getline(in, line)) {
    if (line[0] == '#') {  // the truth, as comment lines
      out += line + "\n";
      continue;
    }
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
    for (std::size_t k = cells.size(); k-- > 0;) out += cells[k] + (k ? "," : "\n");
  }
  return out;
}

}  // namespace

TEST_CASE("gaitopt synth + diagnose end to end", "[ident][cli]") {
  const std::string data = scratch().fresh("data") + ".csv";
  const test::CliRun s = test::runCli("synth --robot " + kRobot + " --gait " + kGait +
                                      " --steps 12 --seed 5 --effect torque_offset@knee_left=-3 --out " +
                                      test::quoted(data));
  REQUIRE(s.exit_code == 0);
  // The truth heads the CSV as '#' lines: one file, published at once.
  CHECK_FALSE(fs::exists(data + ".truth.json"));
  std::istringstream lines(test::readFile(data));
  std::string truth_json;
  for (std::string line; std::getline(lines, line) && line[0] == '#';) truth_json += line.substr(2) + "\n";
  const YAML::Node truth = YAML::Load(truth_json);
  CHECK(truth["effects"][0]["effect"].as<std::string>() == "torque_offset");
  CHECK(truth["effects"][0]["joint"].as<std::string>() == "knee_left");
  CHECK(truth["effects"][0]["value"].as<double>() == -3.0);
  CHECK(truth["seed"].as<int>() == 5);
  const std::string out = scratch().fresh("out");
  const test::CliRun d = test::runCli("diagnose --robot " + kRobot + " --data " + test::quoted(data) +
                                      " --out " + test::quoted(out));
  REQUIRE(d.exit_code == 0);
  // Progress: k of n stages with the elapsed time, the first cause named in its round.
  CHECK_THAT(d.out, Contains("diagnose [1/6] nominal residuals (") &&
                        Contains("diagnose [2/6] screening: ") &&
                        Contains("diagnose [3/6] round 1: torque_offset@knee_left  elapsed ") &&
                        Contains("diagnose [6/6] inertial stage: "));
  const std::string report = test::readFile(out + "/report.md");
  CHECK_THAT(report, Contains("The model overestimates the left-knee torque") &&
                         Contains("a torque-sensor offset of -") &&
                         Contains("N·m on knee_left explains it") &&
                         Contains("on the channels the causes act on"));
  const std::string json = test::readFile(out + "/diagnosis.json");
  CHECK_THAT(json, Contains("\"effect\": \"torque_offset\"") && Contains("\"confounded_with\""));
  const RobotParams extended = loadRobot(out + "/extended_robot.yaml");
  CHECK(extended.sensors.torque_offset[0] == Approx(-3.0).epsilon(0.1));
  CHECK(extended.coulomb == test::robotFile("rabbit_miossec").coulomb);
  CHECK(fs::file_size(out + "/residuals.csv") > 1000);

  // Shuffled columns: the same diagnosis.
  const std::string shuffled = scratch().fresh("shuffled") + ".csv";
  std::ofstream(shuffled) << reversedColumns(test::readFile(data));
  const std::string out2 = scratch().fresh("out");
  const test::CliRun quiet = test::runCli("diagnose --quiet --robot " + kRobot + " --data " +
                                          test::quoted(shuffled) + " --out " + test::quoted(out2));
  REQUIRE(quiet.exit_code == 0);
  CHECK(quiet.out.find("diagnose [") == std::string::npos);
  CHECK(test::readFile(out2 + "/diagnosis.json") == json);
}

TEST_CASE("gaitopt diagnose: bad data stops with exit 2 and writes nothing", "[ident][cli]") {
  const std::string bad = scratch().fresh("bad") + ".csv";
  std::ofstream(bad) << "t,alpha,delta1,delta2,delta3,delta4,phase,stance,step,gamma1,gamma2,gamma3,gamma4\n"
                        "0,0.1,-2.9,-3.1,0.2,-2.8,SS,left,0,1,2,3,4\n"
                        "0.002,0.1,-2.9,-3.1,0.2,nan,SS,left,0,1,2,3,4\n";
  const std::string out = scratch().fresh("out");
  const test::CliRun r = test::runCli("diagnose --robot " + kRobot + " --data " + test::quoted(bad) +
                                      " --out " + test::quoted(out));
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains(":3: row 2, column 'delta4': not a finite number"));
  CHECK_FALSE(fs::exists(out));
  const test::CliRun e = test::runCli("synth --robot " + kRobot + " --gait " + kGait +
                                      " --steps 5 --effect friction@knee=3 --out " +
                                      test::quoted(scratch().fresh("never") + ".csv"));
  CHECK(e.exit_code == 2);
  CHECK_THAT(e.err, Contains("unknown effect 'friction'"));
  // A truth diagnose must refuse as a cause (beyond ±5.6 N·m) is generated.
  const std::string beyond = scratch().fresh("beyond") + ".csv";
  const test::CliRun b = test::runCli("synth --robot " + kRobot + " --gait " + kGait +
                                      " --steps 3 --effect torque_offset@knee_left=12 --out " +
                                      test::quoted(beyond));
  CHECK(b.exit_code == 0);
  CHECK(fs::file_size(beyond) > 10000);
}
