// Measured-data CSV: round trip, column order, and every kind of bad data stopping with a
// message naming the row and column (CLI: exit 2, nothing written).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "gaitopt/io/measured_data.hpp"
#include "gaitopt/io/robot_extensions.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

using namespace gaitopt;
using Catch::Matchers::Contains;

namespace {

test::ScratchDir& scratch() {
  static test::ScratchDir dir("measured", "data");
  return dir;
}

// 3 steps of 20 SS samples, reactions only.
std::vector<std::string> validRows() {
  std::vector<std::string> rows = {"t,alpha,delta1,delta2,delta3,delta4,phase,stance,step,R1x,R1z,R2x,R2z"};
  for (int k = 0; k < 60; ++k)
    rows.push_back(std::to_string(0.002 * k) + ",0.1,-2.9,-3.1,0.2,-2.8,SS," +
                   (k / 20 % 2 ? "right" : "left") + "," + std::to_string(k / 20) + ",1,400,0,0");
  return rows;
}

std::string write(const std::vector<std::string>& rows) {
  std::string text;
  for (const std::string& r : rows) text += r + "\n";
  const std::string path = scratch().fresh("data") + ".csv";
  std::ofstream(path) << text;
  return path;
}

void requireBad(const std::vector<std::string>& rows, const std::string& where) {
  const std::string path = write(rows);
  try {
    readMeasuredCsv(path);
    FAIL("accepted bad data; expected " << where);
  } catch (const ConfigError& e) {
    CHECK_THAT(std::string(e.what()), Contains(path));
    CHECK_THAT(std::string(e.what()), Contains(where));
  }
}

}  // namespace

TEST_CASE("measured data: read back identically, columns in any order", "[ident][io]") {
  const MeasuredData d = readMeasuredCsv(write(validRows()));
  REQUIRE(d.size() == 60);
  CHECK(d.has_reactions);
  CHECK_FALSE(d.has_torque);
  CHECK(d.stance[20] == Stance::Right);
  CHECK(d.step[59] == 2);
  CHECK(d.q[5](2) == -3.1);
  const MeasuredData again = readMeasuredCsv(write({measuredCsv(d)}));
  CHECK(measuredCsv(again) == measuredCsv(d));
  // Columns permuted: the same data.
  std::vector<std::string> swapped;
  for (const std::string& r : validRows()) {
    const auto comma = r.find(',');
    swapped.push_back(r.substr(comma + 1) + "," + r.substr(0, comma));
  }
  CHECK(measuredCsv(readMeasuredCsv(write(swapped))) == measuredCsv(d));
}

TEST_CASE("measured data: comment lines before the header are skipped, rows still counted",
          "[ident][io]") {
  const MeasuredData d = readMeasuredCsv(write(validRows()));
  const std::string with_comment = measuredCsv(d, "{\n  \"seed\": 5\n}\n");
  CHECK(with_comment.rfind("# {\n#   \"seed\": 5\n# }\nt,alpha,", 0) == 0);
  CHECK(measuredCsv(readMeasuredCsv(write({with_comment}))) == measuredCsv(d));
  // Errors keep the file's line and count rows from the header: row 7 is line 3 + 1 + 7.
  std::vector<std::string> rows = validRows();
  rows[7] = "0.012,nan,-2.9,-3.1,0.2,-2.8,SS,left,0,1,400,0,0";
  rows.insert(rows.begin(), {"# a", "#", "# c"});
  requireBad(rows, ":11: row 7, column 'alpha': not a finite number");
  rows[3] = "t,alpha,delta1,delta2,delta3,delta4,phase,stance,step,R1x,R1z,R2x,R2y";
  requireBad(rows, ":4: column 'R2y': unknown column");
  // Only before the header: a '#' line among the rows is a bad row.
  rows = validRows();
  rows.insert(rows.begin() + 5, "# late");
  requireBad(rows, ":6: row 5");
  requireBad({"# only a comment"}, "empty file: expected a header row");
}

TEST_CASE("measured data: optional centres of pressure cop1x, cop2x", "[ident][io]") {
  std::vector<std::string> rows = validRows();
  rows[0] += ",cop1x,cop2x";
  for (std::size_t k = 1; k < rows.size(); ++k) rows[k] += "," + std::to_string(0.01 * k) + ",-0.25";
  const MeasuredData d = readMeasuredCsv(write(rows));
  REQUIRE(d.has_cop);
  REQUIRE(d.cop.size() == 60);
  CHECK(d.cop[4][0] == Approx(0.05));
  CHECK(d.cop[4][1] == -0.25);
  CHECK(measuredCsv(readMeasuredCsv(write({measuredCsv(d)}))) == measuredCsv(d));
  CHECK_FALSE(readMeasuredCsv(write(validRows())).has_cop);
  std::vector<std::string> half = validRows();
  half[0] += ",cop1x";
  for (std::size_t k = 1; k < half.size(); ++k) half[k] += ",0.1";
  requireBad(half, "column 'cop2x': missing: give all of its group or none");
  std::vector<std::string> torque_only;
  for (const std::string& r : validRows()) torque_only.push_back(r + ",0,0");
  torque_only[0] = "t,alpha,delta1,delta2,delta3,delta4,phase,stance,step,gamma1,gamma2,gamma3,gamma4,cop1x,cop2x";
  requireBad(torque_only, "column 'cop1x': centres of pressure need the reaction columns");
  rows[12] = rows[12].substr(0, rows[12].rfind(',')) + ",nan";
  requireBad(rows, "row 12, column 'cop2x': not a finite number");
}

TEST_CASE("measured data: bad data is reported at its row and column", "[ident][io]") {
  std::vector<std::string> rows = validRows();
  SECTION("missing required column") {
    rows[0] = "t,alpha,delta1,delta2,delta3,delta9,phase,stance,step,R1x,R1z,R2x,R2z";
    requireBad(rows, "column 'delta9': unknown column");
  }
  SECTION("NaN") {
    rows[7] = "0.012,nan,-2.9,-3.1,0.2,-2.8,SS,left,0,1,400,0,0";
    requireBad(rows, ":8: row 7, column 'alpha': not a finite number");
  }
  SECTION("inf") {
    rows[9] = "0.016,0.1,-2.9,-3.1,0.2,-2.8,SS,left,0,1,inf,0,0";
    requireBad(rows, "row 9, column 'R1z'");
  }
  SECTION("non-increasing time") {
    rows[4] = "0.004,0.1,-2.9,-3.1,0.2,-2.8,SS,left,0,1,400,0,0";
    requireBad(rows, "row 4, column 't': time must increase");
  }
  SECTION("unknown labels") {
    rows[3] = "0.004,0.1,-2.9,-3.1,0.2,-2.8,XS,left,0,1,400,0,0";
    requireBad(rows, "row 3, column 'phase'");
    rows = validRows();
    rows[3] = "0.004,0.1,-2.9,-3.1,0.2,-2.8,SS,middle,0,1,400,0,0";
    requireBad(rows, "row 3, column 'stance'");
  }
  SECTION("a step with fewer than 20 samples") {
    rows.erase(rows.begin() + 30);
    requireBad(rows, ":22: row 21, column 'step': step 1 has 19 samples");
  }
  SECTION("fewer than 3 steps") {
    rows.resize(41);
    requireBad(rows, "2 steps, fewer than 3");
  }
  SECTION("no torque and no reaction columns") {
    std::vector<std::string> plain;
    for (const std::string& r : validRows()) {
      std::string x = r;
      for (int k = 0; k < 4; ++k) x = x.substr(0, x.rfind(','));
      plain.push_back(x);
    }
    requireBad(plain, "no torque");
  }
  SECTION("binary data") {
    rows[5] += '\0';
    requireBad(rows, ":6: binary data (NUL byte)");
  }
  SECTION("incomplete optional group") {
    for (std::string& r : rows) r = r.substr(0, r.rfind(','));  // drop R2z
    requireBad(rows, "column 'R2z': missing");
  }
}

TEST_CASE("robot file: extension keys are optional, neutral and read back", "[ident][io]") {
  const RobotParams nominal = test::robotFile("rabbit_miossec");
  CHECK(robotExtensionsYaml(nominal).empty());
  CHECK(nominal.sensors.torque_gain[2] == 1.0);
  RobotParams r = nominal;
  r.joint_extras.coulomb[3] = 3.25;
  r.joint_extras.rotor_inertia_factor[0] = 1.5;
  r.sensors.torque_gain[1] = 0.9;
  r.sensors.alpha_offset = 0.02;
  r.sensors.backlash[2] = 0.03;
  r.hip_payload = 4.0;
  r.trunk_com_shift = -0.03;
  r.ground_slope = 0.02;
  const std::string path = scratch().fresh("robot") + ".yaml";
  std::ofstream(path) << test::readFile(test::sourcePath("configs/robot/rabbit_miossec.yaml"))
                      << robotExtensionsYaml(r);
  const RobotParams back = loadRobot(path);
  CHECK(back.joint_extras.coulomb == r.joint_extras.coulomb);
  CHECK(back.joint_extras.rotor_inertia_factor == r.joint_extras.rotor_inertia_factor);
  CHECK(back.sensors.torque_gain == r.sensors.torque_gain);
  CHECK(back.sensors.alpha_offset == 0.02);
  CHECK(back.sensors.backlash == r.sensors.backlash);
  CHECK(back.hip_payload == 4.0);
  CHECK(back.trunk_com_shift == -0.03);
  CHECK(back.ground_slope == 0.02);
  // The payload folds into the trunk like the bar's mass (1.24).
  RobotParams heavier = nominal;
  heavier.bar.equivalent_mass += 4.0;
  RobotParams no_shift = back;
  no_shift.trunk_com_shift = 0.0;
  CHECK(buildModel(no_shift).mass(2) == Approx(buildModel(heavier).mass(2)));
  CHECK(buildModel(no_shift).com_offset(2) == Approx(buildModel(heavier).com_offset(2)));
  const std::string bad = scratch().fresh("robot") + ".yaml";
  std::ofstream(bad) << test::readFile(test::sourcePath("configs/robot/rabbit_miossec.yaml"))
                     << "sensors:\n  torque_gain: {knee_left: -1}\n";
  CHECK_THROWS_WITH(loadRobot(bad), Contains("sensors.torque_gain.knee_left") && Contains("must be > 0"));
}
