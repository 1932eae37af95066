// Robot YAML loading: the shipped robot files, and the ConfigError (file, dotted key, exact
// line) raised for each kind of bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "gaitopt/io/yaml_reader.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using gaitopt::ConfigError;
using gaitopt::loadRobot;
using gaitopt::RobotParams;

namespace {

const double kPi = std::acos(-1.0);

std::string robotFile(const std::string& name) {
  return gaitopt::test::sourcePath("configs/robot/" + name);
}

// Scratch directory for the bad files, removed when the test binary exits.
gaitopt::test::ScratchDir& scratch() {
  static gaitopt::test::ScratchDir dir("robot_yaml", "robot");
  return dir;
}

// A valid robot document; the numbers on the right are the 1-based line numbers that the
// error tests below assert.
const std::vector<std::string> kValidRobot = {
    "# provenance: written by test_robot_yaml.cpp",                                      // 1
    "name: test_robot",                                                                  // 2
    "lengths: {l1: 0.4, l2: 0.4, l4: 0.4, l5: 0.4}",                                     // 3
    "com_offsets: {s1: 0.127, s2: 0.163, s3: 0.20025, s4: 0.163, s5: 0.127}",            // 4
    "masses:",                                                                           // 5
    "  m1: 3.2",                                                                         // 6
    "  m2: 6.8",                                                                         // 7
    "  m3: 16.0",                                                                        // 8
    "  m4: 6.8",                                                                         // 9
    "  m5: 3.2",                                                                         // 10
    "inertias: {I1: 0.1, I2: 0.25, I3: 2.22, I4: 0.25, I5: 0.1}",                        // 11
    "motors:",                                                                           // 12
    "  rotor_inertia: [3.32e-4, 3.32e-4, 3.32e-4, 3.32e-4]",                             // 13
    "  gear_ratio: 50",                                                                  // 14
    "  torque_constant: 0.16",                                                           // 15
    "  resistance: 0.96",                                                                // 16
    "  envelope: {speed: [0, 5.45, 10.47, 12.15], torque: [140, 140, 60, 0]}",           // 17
    "friction:",                                                                         // 18
    "  coulomb: [5.48, 16.5, 16.5, 5.48]",                                               // 19
    "  viscous:",                                                                        // 20
    "    - 8.84",                                                                        // 21
    "    - 15.0",                                                                        // 22
    "    - 15.0",                                                                        // 23
    "    - 8.84",                                                                        // 24
    "joint_limits_deg: {hip_min: -260, hip_max: -110, knee_min: -230, knee_max: -127}",  // 25
    "gravity: 9.81",                                                                     // 26
    "support_bar:",                                                                      // 27
    "  equivalent_mass: 7.5",                                                            // 28
    "trunk_length: 0.625",                                                               // 29
};

// kValidRobot with some lines (1-based) replaced; "#" blanks a line without shifting others.
std::string robotWith(const std::map<int, std::string>& replaced = {}) {
  return gaitopt::test::withLines(kValidRobot, replaced);
}

// Loading `yaml` must throw a ConfigError for `key` at `line`, with the standard message.
void requireError(const std::string& yaml, const std::string& key, int line,
                  const std::string& problem = "") {
  gaitopt::test::requireConfigError(loadRobot, scratch().write(yaml), key, line,
                                    problem);
}

}  // namespace

TEST_CASE("ConfigError message names file, line and key", "[robot_yaml]") {
  const ConfigError with_line("robot.yaml", "masses.m3", 8, "must be > 0");
  CHECK(std::string(with_line.what()) == "robot.yaml:8: key 'masses.m3': must be > 0");
  const ConfigError without_line("robot.yaml", "masses.m3", 0, "must be > 0");
  CHECK(std::string(without_line.what()) == "robot.yaml: key 'masses.m3': must be > 0");
  const ConfigError file_level("robot.yaml", "", 3, "invalid YAML");
  CHECK(std::string(file_level.what()) == "robot.yaml:3: invalid YAML");
}

TEST_CASE("default robot file: Miossec Table 1.1 with the 7.5 kg bar", "[robot_yaml]") {
  const RobotParams r = loadRobot(robotFile("rabbit_miossec.yaml"));
  CHECK(r.name == "rabbit_miossec");
  CHECK(r.source_file == robotFile("rabbit_miossec.yaml"));
  CHECK(r.l1 == 0.4);
  CHECK(r.l2 == 0.4);
  CHECK(r.l4 == 0.4);
  CHECK(r.l5 == 0.4);
  CHECK(r.s == std::array<double, 5>{0.127, 0.163, 0.20025, 0.163, 0.127});
  CHECK(r.mass == std::array<double, 5>{3.2, 6.8, 16.0, 6.8, 3.2});
  CHECK(r.inertia == std::array<double, 5>{0.1, 0.25, 2.22, 0.25, 0.1});
  CHECK(r.rotor_inertia == std::array<double, 4>{3.32e-4, 3.32e-4, 3.32e-4, 3.32e-4});
  CHECK(r.gear_ratio == 50.0);
  CHECK(r.motor_torque_constant == 0.16);
  CHECK(r.motor_resistance == 0.96);
  CHECK(r.coulomb == std::array<double, 4>{5.48, 16.5, 16.5, 5.48});
  CHECK(r.viscous == std::array<double, 4>{8.84, 15.0, 15.0, 8.84});
  CHECK(r.envelope.speed == std::array<double, 4>{0.0, 5.45, 10.47, 12.15});
  CHECK(r.envelope.torque == std::array<double, 4>{140.0, 140.0, 60.0, 0.0});
  CHECK(r.limits.hip_min == Approx(-4.537856055185257).margin(1e-15));  // -260° (3.39)
  CHECK(r.limits.hip_max == Approx(-1.9198621771937625).margin(1e-15));
  CHECK(r.limits.knee_min == Approx(-4.014257279586958).margin(1e-15));
  CHECK(r.limits.knee_max == Approx(-2.2165681500327987).margin(1e-15));
  CHECK(r.gravity == 9.81);
  CHECK(r.bar.present);
  CHECK_FALSE(r.bar.from_geometry);
  CHECK(r.bar.equivalent_mass == 7.5);
  CHECK(r.trunk_length == 0.625);
}

TEST_CASE("no-bar robot file: Table 1.1 without bar, default envelope and limits",
          "[robot_yaml]") {
  const RobotParams r = loadRobot(robotFile("rabbit_miossec_nobar.yaml"));
  CHECK(r.name == "rabbit_miossec_nobar");
  CHECK_FALSE(r.bar.present);
  CHECK(r.mass[2] == 16.0);
  CHECK(r.gear_ratio == 50.0);
  CHECK(r.limits.hip_min == Approx(-260.0 * kPi / 180.0).margin(1e-15));
  CHECK(r.limits.knee_max == Approx(-127.0 * kPi / 180.0).margin(1e-15));
  CHECK(r.envelope.torque == std::array<double, 4>{140.0, 140.0, 60.0, 0.0});
  CHECK(r.gravity == 9.81);
}

TEST_CASE("bar-geometry robot file gives m_eq = 7.5 kg by (1.29)", "[robot_yaml]") {
  const RobotParams r = loadRobot(robotFile("rabbit_miossec_bar_geometry.yaml"));
  CHECK(r.bar.present);
  CHECK(r.bar.from_geometry);
  CHECK(r.bar.bar_length == 3.0);
  CHECK(r.bar.overhang == 0.5);
  CHECK(r.bar.bar_mass == 15.0);
  CHECK(r.bar.counterweight_mass == 7.5);
  CHECK(r.bar.equivalent_mass == Approx(7.5).margin(1e-12));
  CHECK(r.mass == loadRobot(robotFile("rabbit_miossec.yaml")).mass);
}

TEST_CASE("Chevallereau-Aoustin (WGK 2003 / Kelly 2017) robot file", "[robot_yaml]") {
  const RobotParams r = loadRobot(robotFile("rabbit_chevallereau_aoustin.yaml"));
  CHECK(r.mass == std::array<double, 5>{3.2, 6.8, 20.0, 6.8, 3.2});
  CHECK(r.inertia == std::array<double, 5>{0.93, 1.08, 2.22, 1.08, 0.93});
  CHECK(r.s == std::array<double, 5>{0.128, 0.163, 0.20, 0.163, 0.128});
  CHECK(r.rotor_inertia == std::array<double, 4>{});
  CHECK(r.coulomb == std::array<double, 4>{});
  CHECK(r.viscous == std::array<double, 4>{});
  CHECK_FALSE(r.bar.present);
  CHECK(r.trunk_length == 0.625);
  // The lumped link inertias are Table 1.1's plus one reflected rotor, N² I_m = 0.83.
  const double reflected = 50.0 * 50.0 * 3.32e-4;
  CHECK(r.inertia[0] == Approx(0.1 + reflected).margin(1e-12));
  CHECK(r.inertia[1] == Approx(0.25 + reflected).margin(1e-12));
}

TEST_CASE("Chesse robot file: Table 1.1 bodies, 20 kg trunk, no rotor, friction or bar",
          "[robot_yaml]") {
  const RobotParams r = loadRobot(robotFile("rabbit_chesse.yaml"));
  CHECK(r.mass == std::array<double, 5>{3.2, 6.8, 20.0, 6.8, 3.2});
  CHECK(r.inertia == std::array<double, 5>{0.1, 0.25, 2.22, 0.25, 0.1});
  CHECK(r.s == std::array<double, 5>{0.127, 0.163, 0.20025, 0.163, 0.127});
  CHECK(r.rotor_inertia == std::array<double, 4>{});
  CHECK(r.coulomb == std::array<double, 4>{});
  CHECK(r.viscous == std::array<double, 4>{});
  CHECK_FALSE(r.bar.present);
}

TEST_CASE("human five-link file: no motors and no friction sections mean none",
          "[robot_yaml]") {
  const RobotParams r = loadRobot(robotFile("human_subject01.yaml"));
  // lump-osim's output of the scaled model: symmetric legs, the model's 72.6 kg (the trial's
  // README), the trunk CoM 0.3869 m above and 0.0470 m behind the hips.
  CHECK(r.mass[0] == r.mass[4]);
  CHECK(r.mass[1] == r.mass[3]);
  CHECK(r.mass[0] + r.mass[1] + r.mass[2] + r.mass[3] + r.mass[4] == Approx(72.6).margin(1e-4));
  CHECK(r.l1 == r.l5);
  CHECK(r.l2 == r.l4);
  CHECK(r.s[2] == Approx(std::hypot(0.3869, 0.0470)).margin(1e-4));
  CHECK(r.rotor_inertia == std::array<double, 4>{});
  CHECK(r.coulomb == std::array<double, 4>{});
  CHECK(r.viscous == std::array<double, 4>{});
  CHECK(r.gravity == 9.80665);
  CHECK_FALSE(r.bar.present);
  // A present motors section must still be complete.
  requireError(robotWith({{13, "#"}}), "motors.rotor_inertia", 12);
}

TEST_CASE("CSM 2003 robot file", "[robot_yaml]") {
  const RobotParams r = loadRobot(robotFile("rabbit_csm2003.yaml"));
  CHECK(r.mass == std::array<double, 5>{3.2, 6.8, 12.0, 6.8, 3.2});
  CHECK(r.inertia == std::array<double, 5>{0.20, 0.47, 1.33, 0.47, 0.20});
  CHECK(r.s == std::array<double, 5>{0.24, 0.11, 0.24, 0.11, 0.24});
  CHECK(r.rotor_inertia == std::array<double, 4>{3.32e-4, 3.32e-4, 3.32e-4, 3.32e-4});
  CHECK(r.gear_ratio == 50.0);
  CHECK(r.coulomb == std::array<double, 4>{});
  CHECK(r.motor_torque_constant == 0.16);
  CHECK(r.motor_resistance == 0.96);
  CHECK_FALSE(r.bar.present);
  CHECK(r.trunk_length == 0.625);
}

TEST_CASE("every shipped robot file loads and starts with a provenance comment",
          "[robot_yaml]") {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(robotFile(""))) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    INFO(entry.path());
    std::ifstream in(entry.path());
    std::string first_line;
    std::getline(in, first_line);
    CHECK(first_line.rfind("# provenance:", 0) == 0);
    const RobotParams r = loadRobot(entry.path().string());
    CHECK(r.name == entry.path().stem().string());
  }
  CHECK(files >= 6);
}

TEST_CASE("the test document itself is valid", "[robot_yaml]") {
  const RobotParams r = loadRobot(scratch().write(robotWith()));
  CHECK(r.name == "test_robot");
  CHECK(r.viscous == std::array<double, 4>{8.84, 15.0, 15.0, 8.84});
  CHECK(r.bar.equivalent_mass == 7.5);
}

TEST_CASE("missing key: named with the line of its parent mapping", "[robot_yaml]") {
  requireError(robotWith({{8, "#"}}), "masses.m3", 5);
  requireError(robotWith({{14, "  gear_ration: 50"}}), "motors.gear_ratio", 12);
  // The root mapping starts at its first entry, after the provenance comment.
  requireError(robotWith({{11, "#"}}), "inertias", 2);
  // An empty support_bar section is neither of the two bar forms.
  requireError(robotWith({{28, "#"}}), "support_bar", 27);
}

TEST_CASE("wrong type", "[robot_yaml]") {
  requireError(robotWith({{8, "  m3: heavy"}}), "masses.m3", 8);
  requireError(robotWith({{8, "  m3: \"16\""}}), "masses.m3", 8);  // quoted = text
  requireError(robotWith({{8, "  m3: .nan"}}), "masses.m3", 8);
  requireError(robotWith({{8, "  m3: .inf"}}), "masses.m3", 8);
  requireError(robotWith({{8, "  m3: [16]"}}), "masses.m3", 8);
  requireError(robotWith({{14, "  gear_ratio: {N: 50}"}}), "motors.gear_ratio", 14);
  requireError(robotWith({{19, "  coulomb: 5.48"}}), "friction.coulomb", 19);
  requireError(robotWith({{22, "    - fast"}}), "friction.viscous[1]", 22);
  requireError(robotWith({{2, "name: [a, b]"}}), "name", 2);
  requireError(robotWith({{3, "lengths: 0.4"}}), "lengths", 3);
}

TEST_CASE("unknown key, at any depth", "[robot_yaml]") {
  requireError(robotWith({{1, "colour: red"}}), "colour", 1);
  requireError(robotWith({{3, "lengths: {l1: 0.4, l2: 0.4, l3: 0.6, l4: 0.4, l5: 0.4}"}}),
               "lengths.l3", 3);
  requireError(robotWith({{29, "  mass: 3"}}), "support_bar.mass", 29);
  requireError(
      robotWith({{17, "  envelope: {speed: [0, 1, 2, 3], torque: [1, 1, 1, 0], x: 1}"}}),
      "motors.envelope.x", 17);
}

TEST_CASE("duplicate key", "[robot_yaml]") {
  requireError(robotWith({{10, "  m4: 6.9"}}), "masses.m4", 10);
}

TEST_CASE("wrong sequence length", "[robot_yaml]") {
  requireError(robotWith({{19, "  coulomb: [5.48, 16.5, 16.5]"}}), "friction.coulomb", 19);
  requireError(robotWith({{24, "    - 8.84\n    - 1.0"}}), "friction.viscous", 20);
  requireError(robotWith({{13, "  rotor_inertia: []"}}), "motors.rotor_inertia", 13);
  requireError(robotWith({{17, "  envelope: {speed: [0, 5.45, 10.47], torque: [140, 140, 60]}"}}),
               "motors.envelope.speed", 17);
}

TEST_CASE("unparsable or missing file", "[robot_yaml]") {
  const std::string path = scratch().write(robotWith({{9, "   m4: 6.8"}}));
  try {
    loadRobot(path);
    FAIL("no ConfigError for bad indentation");
  } catch (const ConfigError& e) {
    CHECK(e.file() == path);
    CHECK(e.key().empty());
    CHECK(e.line() == 9);
    CHECK_THAT(std::string(e.what()), Contains(path + ":9: invalid YAML"));
  }
  const std::string missing = robotFile("no_such_robot.yaml");
  try {
    loadRobot(missing);
    FAIL("no ConfigError for a missing file");
  } catch (const ConfigError& e) {
    CHECK(e.file() == missing);
    CHECK(e.line() == 0);
    CHECK_THAT(std::string(e.what()), Contains(missing + ": "));
  }
  // A document that is not a mapping at all.
  const std::string list = scratch().write("- 1\n- 2\n");
  CHECK_THROWS_WITH(loadRobot(list), Contains(list + ":1: expected a mapping"));
}

TEST_CASE("non-physical body values", "[robot_yaml]") {
  requireError(robotWith({{8, "  m3: 0"}}), "masses.m3", 8);
  requireError(robotWith({{6, "  m1: -3.2"}}), "masses.m1", 6);
  requireError(robotWith({{3, "lengths: {l1: 0.4, l2: -0.4, l4: 0.4, l5: 0.4}"}}), "lengths.l2", 3);
  requireError(robotWith({{3, "lengths: {l1: 0.4, l2: 0.4, l4: 0.4, l5: 0}"}}), "lengths.l5", 3);
  requireError(robotWith({{4, "com_offsets: {s1: 0.127, s2: 0.163, s3: 0, s4: 0.163, s5: 0.127}"}}),
               "com_offsets.s3", 4);
  requireError(robotWith({{11, "inertias: {I1: 0.1, I2: 0.25, I3: 0, I4: 0.25, I5: 0.1}"}}),
               "inertias.I3", 11);
  requireError(robotWith({{11, "inertias: {I1: 0.1, I2: 0.25, I3: 2.22, I4: 0.25, I5: -0.1}"}}),
               "inertias.I5", 11);
  requireError(robotWith({{2, "name: \"\""}}), "name", 2);
}

TEST_CASE("non-physical motor, friction and limit values", "[robot_yaml]") {
  requireError(robotWith({{14, "  gear_ratio: 0"}}), "motors.gear_ratio", 14);
  requireError(robotWith({{14, "  gear_ratio: -50"}}), "motors.gear_ratio", 14);
  requireError(robotWith({{13, "  rotor_inertia: [3.32e-4, -1e-4, 3.32e-4, 3.32e-4]"}}),
               "motors.rotor_inertia[1]", 13);
  requireError(robotWith({{15, "  torque_constant: 0"}}), "motors.torque_constant", 15);
  requireError(robotWith({{16, "  resistance: -0.96"}}), "motors.resistance", 16);
  requireError(robotWith({{19, "  coulomb: [5.48, -16.5, 16.5, 5.48]"}}), "friction.coulomb[1]",
               19);
  requireError(robotWith({{23, "    - -15.0"}}), "friction.viscous[2]", 23);
  requireError(robotWith({{26, "gravity: 0"}}), "gravity", 26);
  requireError(robotWith({{25, "joint_limits_deg: {hip_min: -100, hip_max: -110, knee_min: -230, "
                               "knee_max: -127}"}}),
               "joint_limits_deg.hip_min", 25);
  requireError(robotWith({{25, "joint_limits_deg: {hip_min: -260, hip_max: -110, knee_min: -127, "
                               "knee_max: -127}"}}),
               "joint_limits_deg.knee_min", 25);
  requireError(robotWith({{17, "  envelope: {speed: [0, 5.45, 5.45, 12.15], "
                               "torque: [140, 140, 60, 0]}"}}),
               "motors.envelope.speed[2]", 17);
  requireError(robotWith({{17, "  envelope: {speed: [0, 5.45, 10.47, 12.15], "
                               "torque: [140, 140, 60, -1]}"}}),
               "motors.envelope.torque[3]", 17);
}

TEST_CASE("support bar: one form only, physical values", "[robot_yaml]") {
  const std::string geometry =
      "  geometry: {bar_length: 3.0, overhang: 0.5, bar_mass: 15.0, counterweight_mass: 7.5}";
  requireError(robotWith({{29, geometry}}), "support_bar.geometry", 29);  // both forms
  requireError(robotWith({{28, "  equivalent_mass: -1"}}), "support_bar.equivalent_mass", 28);
  requireError(robotWith({{28, "  geometry: {bar_length: 0.5, overhang: 0.5, bar_mass: 15.0, "
                               "counterweight_mass: 7.5}"}}),
               "support_bar.geometry.overhang", 28);
  requireError(robotWith({{28, "  geometry: {bar_length: 3.0, overhang: 0.5, bar_mass: 0, "
                               "counterweight_mass: 7.5}"}}),
               "support_bar.geometry.bar_mass", 28);
  // Light bar, heavy counterweight: (1.29) gives (1·1.5 − 7.5·0.5)/2.5 < 0.
  requireError(robotWith({{28, "  geometry: {bar_length: 3.0, overhang: 0.5, bar_mass: 1.0, "
                               "counterweight_mass: 7.5}"}}),
               "support_bar.geometry", 28);
  const RobotParams r = loadRobot(scratch().write(robotWith({{28, geometry}})));
  CHECK(r.bar.equivalent_mass == Approx(7.5).margin(1e-12));
}

TEST_CASE("robot numbers outside their documented physical ranges", "[robot_yaml][reliability]") {
  // Echoed as written, with the range and unit.
  requireError(robotWith({{6, "  m1: 1e300"}}), "masses.m1", 6,
               "must be in [0.001, 1000] kg, got 1e300");
  requireError(robotWith({{6, "  m1: 4.9e-324"}}), "masses.m1", 6, "got 4.9e-324");  // denormal
  requireError(robotWith({{3, "lengths: {l1: 0.4, l2: 0.4, l4: 0.4, l5: 1e9}"}}), "lengths.l5", 3,
               "[0.001, 10] m");
  requireError(robotWith({{11, "inertias: {I1: 0.1, I2: 0.25, I3: 2e9, I4: 0.25, I5: 0.1}"}}),
               "inertias.I3", 11, "kg m^2");
  requireError(robotWith({{14, "  gear_ratio: 0.5"}}), "motors.gear_ratio", 14, "[1, 10000]");
  requireError(robotWith({{19, "  coulomb: [5.48, 16.5, 1e6, 5.48]"}}), "friction.coulomb[2]",
               19, "got 1e6");
  requireError(robotWith({{26, "gravity: 0.2e3"}}), "gravity", 26, "got 0.2e3");
  // The centre of mass lies within its link: s1 from the knee along l1, s3 along the trunk.
  requireError(robotWith({{4, "com_offsets: {s1: 0.5, s2: 0.163, s3: 0.20025, s4: 0.163, "
                              "s5: 0.127}"}}),
               "com_offsets.s1", 4, "within its link: 0.5 m > l1 = 0.4 m");
  requireError(robotWith({{29, "trunk_length: 0.1"}}), "com_offsets.s3", 4, "trunk_length");
}

TEST_CASE("YamlMap: strings, booleans, optional values", "[robot_yaml]") {
  const YAML::Node node = YAML::Load("a: text\nb: true\nc: 'yes'\nd: 2\ne1: yes\ne2: On\n");
  const gaitopt::YamlMap m(node, "mem.yaml", "top");
  CHECK(m.string("a") == "text");
  CHECK(m.boolean("b"));
  CHECK_THROWS_WITH(m.boolean("c"), Contains("mem.yaml:3: key 'top.c'"));
  // Only true/false, not the YAML 1.1 spellings.
  CHECK_THROWS_WITH(m.boolean("e1"), Contains("mem.yaml:5: key 'top.e1': expected true or false"));
  CHECK_THROWS_WITH(m.boolean("e2"), Contains("got 'On'"));
  CHECK(m.optionalNumber("d") == 2.0);
  CHECK_FALSE(m.optionalNumber("e").has_value());
  CHECK_FALSE(m.optionalMap("f").has_value());
  CHECK(m.has("a"));
  CHECK_FALSE(m.has("e"));
  CHECK_NOTHROW(m.rejectUnknownKeys());
}

TEST_CASE("joint_limits_deg given in radians is refused", "[robot_yaml]") {
  requireError(robotWith({{25, "joint_limits_deg: {hip_min: -4.5, hip_max: -1.9, knee_min: -4.0, "
                               "knee_max: -2.2}"}}),
               "joint_limits_deg.hip_min", 25, "looks like radians (-4.5 to -1.9)");
  // Degrees that happen to be small stay degrees when the range is a real joint's.
  RobotParams r;
  REQUIRE_NOTHROW(r = loadRobot(scratch().write(robotWith(
                      {{25, "joint_limits_deg: {hip_min: -5, hip_max: 120, knee_min: -230, "
                            "knee_max: -127}"}}))));
  CHECK(r.limits.hip_min == Approx(-5.0 * kPi / 180.0));
}
