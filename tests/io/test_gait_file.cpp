// Gait files (loadGaitFile, parseGaitOptions, gaitYaml) and summary.json: the shipped example,
// exact round trips, ConfigError (file, dotted key, line) for each kind of bad input, and the
// summary's constraint groups.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/constraint_summary.hpp"
#include "gaitopt/io/summary_file.hpp"
#include "gaitopt/io/trajectory_file.hpp"
#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/yaml_reader.hpp"
#include "test_files.hpp"
#include "test_gait_document.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using gaitopt::ConfigError;
using gaitopt::GaitFile;
using gaitopt::GaitOptions;
using gaitopt::GaitParameters;
using gaitopt::loadGaitFile;
using gaitopt::ModelOptions;
using gaitopt::test::gaitWith;
using gaitopt::test::readFile;
using gaitopt::test::sourcePath;

namespace {

const std::string kExample = sourcePath("configs/gait/default_step.yaml");
const std::string kRobot = sourcePath("configs/robot/rabbit_miossec.yaml");

// Scratch directory for gait files and command outputs, removed when the test binary exits.
gaitopt::test::ScratchDir& scratch() {
  static gaitopt::test::ScratchDir dir("gait_io", "gait");
  return dir;
}

// A hand-made defined step that violates level 5 (tests/test_gait_support.hpp: definedStep).
const double kExampleValues[gaitopt::kNumGaitParameters] = {
    -0.044819, -2.593492, 1.520796, 0.35, -0.190837, -2.495513, 1.520796, -2.445513, 1.520796,
    0.0,       0.06,      -0.9,     0.3,  0.3,       0.3,       0.3,       0.12};

// Loading `yaml` must throw a ConfigError for `key` at `line`, with the standard message.
void requireError(const std::string& yaml, const std::string& key, int line,
                  const std::string& problem = "") {
  gaitopt::test::requireConfigError(loadGaitFile, scratch().write(yaml), key, line,
                                    problem);
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void requireSameOptions(const GaitOptions& a, const GaitOptions& b) {
  CHECK(sameBits(a.friction_coefficient, b.friction_coefficient));
  CHECK(sameBits(a.clearance_height, b.clearance_height));
  CHECK(sameBits(a.min_normal_force, b.min_normal_force));
  CHECK(a.dry_friction == b.dry_friction);
  CHECK(a.ds_distribution == b.ds_distribution);
  CHECK(sameBits(a.sample_rate, b.sample_rate));
  CHECK(a.ss_nodes == b.ss_nodes);
  CHECK(a.ds_nodes == b.ds_nodes);
  CHECK(a.criteria_refinement == b.criteria_refinement);
  CHECK(sameBits(a.f_min, b.f_min));
  CHECK(sameBits(a.alphadot_margin, b.alphadot_margin));
  CHECK(sameBits(a.ds_alphadot_max, b.ds_alphadot_max));
  CHECK(sameBits(a.angle_margin, b.angle_margin));
  CHECK(sameBits(a.reach_margin, b.reach_margin));
  CHECK(sameBits(a.kappa_min, b.kappa_min));
  CHECK(sameBits(a.joint_limit_margin, b.joint_limit_margin));
  CHECK(a.full_torque_envelope == b.full_torque_envelope);
  CHECK(sameBits(a.target_speed, b.target_speed));
}

}  // namespace

TEST_CASE("the shipped example gait file loads and defines a step", "[gait_io]") {
  const GaitFile g = loadGaitFile(kExample);
  CHECK(g.path == kExample);
  CHECK(fs::equivalent(g.robot_path, kRobot));
  CHECK(g.robot_path == fs::path(kRobot).lexically_normal().string());
  CHECK(g.robot.name == "rabbit_miossec");
  REQUIRE(g.parameters.size() == gaitopt::kNumGaitParameters);
  GaitOptions defaults;
  defaults.sample_rate = 1000.0;
  defaults.target_speed = 0.5;  // written by gaitopt optimize from configs/default.yaml
  defaults.friction_coefficient = 0.6;  // the playback margin of configs/default.yaml
  requireSameOptions(g.options, defaults);
  CHECK(g.model_options.rotor == gaitopt::RotorModel::Exact);
  CHECK(g.model_options.friction_smoothing == ModelOptions{}.friction_smoothing);

  // As its comment says: an optimised step on which every constraint holds strictly, at the
  // speed it was optimised for.
  const gaitopt::GaitEvaluator ev(g.robot, g.options, g.model_options);
  const auto e = ev.evaluate(g.parameters);
  CHECK(e.defined());
  CHECK(e.motion_computed);
  CHECK(e.failed_level == -1);
  CHECK(e.speed == Approx(0.5).margin(1e-6));
}

TEST_CASE("gait files of a richer parameterisation round-trip", "[gait_io]") {
  GaitOptions o;
  o.parameterisation.ss_points = 3;
  o.parameterisation.ds_points = 1;
  GaitParameters p(o.parameterisation.size());
  for (int i = 0; i < p.size(); ++i) p(i) = i < gaitopt::kNumGaitParameters ? kExampleValues[i] : 0.01 * i;
  const std::string path = scratch().write(gaitopt::gaitYaml(kRobot, p, o, ModelOptions{}), "rich");
  const GaitFile g = loadGaitFile(path);
  CHECK(g.options.parameterisation == o.parameterisation);
  REQUIRE(g.parameters.size() == p.size());
  for (int i = 0; i < p.size(); ++i) CHECK(g.parameters(i) == p(i));
  CHECK(readFile(path).find("delta1_ss25:") != std::string::npos);
  CHECK(readFile(path).find("theta3_ds50:") != std::string::npos);
}

TEST_CASE("gaitYaml round-trips parameters and options bit for bit", "[gait_io]") {
  GaitParameters p(gaitopt::kNumGaitParameters);
  for (int i = 0; i < gaitopt::kNumGaitParameters; ++i) p(i) = kExampleValues[i];
  p(gaitopt::kStepLength) = 0.1 + 0.2;  // not the shortest decimal of itself
  p(gaitopt::kAlphaIDS) = -1.0 / 3.0;
  p(gaitopt::kX2rInt) = -1e-300;
  p(gaitopt::kZ2Int) = 5e-324;  // smallest subnormal
  p(gaitopt::kDelta1sISS) = -0.0;
  p(gaitopt::kTDS) = std::nextafter(0.12, 1.0);

  GaitOptions o;
  o.friction_coefficient = 0.7 + 1e-16;
  o.clearance_height = 0.0;
  o.min_normal_force = 1.0 / 7.0;
  o.dry_friction = true;
  o.ds_distribution = gaitopt::DsDistribution::Energy;
  o.sample_rate = 333.3;
  o.ss_nodes = 2;
  o.ds_nodes = 512;
  o.criteria_refinement = 3;
  o.f_min = 1e-7;
  o.alphadot_margin = 0.0;
  o.ds_alphadot_max = -1e-12;
  o.angle_margin = 0.2 / 3.0;  // a round-trip test value within (0, 0.1]
  o.reach_margin = 1.5e-5;
  o.kappa_min = 0.3;
  o.joint_limit_margin = 0.01;
  o.full_torque_envelope = false;
  o.target_speed = 0.3;
  ModelOptions mo;
  mo.rotor = gaitopt::RotorModel::HighGear;
  mo.friction_smoothing = 0.1 / 3.0;

  SECTION("robot path relative to the gait file's directory") {
    const fs::path sub = scratch().dir() / "robots";
    fs::create_directories(sub);
    fs::copy_file(kRobot, sub / "robot.yaml", fs::copy_options::overwrite_existing);
    const std::string text = gaitYaml("robots/robot.yaml", p, o, mo);
    CHECK_THAT(text, Contains("written by gaitopt"));
    const std::string path = scratch().write(text);
    const GaitFile g = loadGaitFile(path);
    CHECK(fs::equivalent(g.robot_path, sub / "robot.yaml"));
    CHECK(g.robot.name == "rabbit_miossec");
    for (int i = 0; i < gaitopt::kNumGaitParameters; ++i) {
      INFO(gaitopt::kGaitParameterNames[i] << " " << p(i) << " read back as " << g.parameters(i));
      CHECK(sameBits(g.parameters(i), p(i)));
    }
    requireSameOptions(g.options, o);
    CHECK(g.model_options.rotor == mo.rotor);
    CHECK(sameBits(g.model_options.friction_smoothing, mo.friction_smoothing));
  }
  SECTION("default options and an absolute robot path that needs quoting") {
    const fs::path odd = scratch().dir() / "a dir: with \"quotes\"";
    fs::create_directories(odd);
    fs::copy_file(kRobot, odd / "r.yaml", fs::copy_options::overwrite_existing);
    const std::string path =
        scratch().write(gaitYaml((odd / "r.yaml").string(), p, GaitOptions{}, ModelOptions{}));
    const GaitFile g = loadGaitFile(path);
    CHECK(fs::equivalent(g.robot_path, odd / "r.yaml"));
    for (int i = 0; i < gaitopt::kNumGaitParameters; ++i) CHECK(sameBits(g.parameters(i), p(i)));
    requireSameOptions(g.options, GaitOptions{});
  }
}

TEST_CASE("parseGaitOptions works on any options mapping", "[gait_io]") {
  const YAML::Node root = YAML::Load(
      "optimizer:\n"
      "  options:\n"
      "    target_speed: 0.5\n"
      "    rotor: high_gear\n"
      "    ss_nodes: 40\n");
  const gaitopt::YamlMap doc(root, "opt.yaml", "");
  ModelOptions mo;
  const GaitOptions o = gaitopt::parseGaitOptions(doc.map("optimizer").map("options"), mo);
  CHECK(o.target_speed == 0.5);
  CHECK(o.ss_nodes == 40);
  CHECK(o.ds_nodes == GaitOptions{}.ds_nodes);
  CHECK(mo.rotor == gaitopt::RotorModel::HighGear);

  const YAML::Node bad = YAML::Load("opts:\n  kappa_min: 0\n");
  const gaitopt::YamlMap bad_doc(bad, "opt.yaml", "");
  try {
    gaitopt::parseGaitOptions(bad_doc.map("opts"), mo);
    FAIL("no ConfigError");
  } catch (const ConfigError& e) {
    CHECK(e.key() == "opts.kappa_min");
    CHECK(e.line() == 2);
  }
}

TEST_CASE("bad gait files name the file, the key and its line", "[gait_io]") {
  SECTION("the unmodified document loads") { CHECK_NOTHROW(loadGaitFile(scratch().write(gaitWith()))); }
  SECTION("missing parameter: reported at the parameters mapping") {
    requireError(gaitWith({{7, "#"}}), "parameters.d", 3);
  }
  SECTION("unknown parameter") {
    requireError(gaitWith({{20, "  T_DS: 0.12\n  T_SS: 0.4"}}), "parameters.T_SS", 21);
  }
  SECTION("wrong type") {
    requireError(gaitWith({{7, "  d: far"}}), "parameters.d", 7);
    requireError(gaitWith({{7, "  d: \"0.35\""}}), "parameters.d", 7);
    requireError(gaitWith({{7, "  d: [0.35]"}}), "parameters.d", 7);
    requireError(gaitWith({{21, "options: 5"}, {22, "#"}, {23, "#"}, {24, "#"}}), "options", 21);
  }
  SECTION("non-positive step length or DS duration") {
    requireError(gaitWith({{7, "  d: 0"}}), "parameters.d", 7);
    requireError(gaitWith({{20, "  T_DS: -0.1"}}), "parameters.T_DS", 20);
  }
  SECTION("unknown option or top-level key") {
    requireError(gaitWith({{22, "  sample_rat: 1000"}}), "options.sample_rat", 22);
    requireError(gaitWith({{1, "speed: 0.5"}}), "speed", 1);
  }
  SECTION("bad enumerations") {
    requireError(gaitWith({{23, "  ds_distribution: power"}}), "options.ds_distribution", 23);
    requireError(gaitWith({{23, "  rotor: geared"}}), "options.rotor", 23);
    requireError(gaitWith({{23, "  dry_friction: maybe"}}), "options.dry_friction", 23);
  }
  SECTION("node counts must be integers from 2 to 512") {
    requireError(gaitWith({{24, "  ss_nodes: 32.5"}}), "options.ss_nodes", 24);
    requireError(gaitWith({{24, "  ss_nodes: 1"}}), "options.ss_nodes", 24);
    requireError(gaitWith({{24, "  ds_nodes: 513"}}), "options.ds_nodes", 24);
  }
  SECTION("criteria_refinement: an integer from 1 to 4, ss_nodes times it at most 1024") {
    const auto with = [](const std::string& ss_nodes, const std::string& refinement) {
      return gaitWith({{24, "  ss_nodes: " + ss_nodes + "\n  criteria_refinement: " + refinement}});
    };
    const std::string range = "must be an integer from 1 to 4";
    requireError(with("32", "0"), "options.criteria_refinement", 25, range + ", got 0");
    requireError(with("32", "5"), "options.criteria_refinement", 25, range + ", got 5");
    requireError(with("32", "1.5"), "options.criteria_refinement", 25, range + ", got 1.5");
    requireError(with("512", "3"), "options.criteria_refinement", 25,
                 "ss_nodes * criteria_refinement must be at most 1024, got 512 * 3");
  }
  SECTION("out-of-range option values") {
    requireError(gaitWith({{22, "  sample_rate: 0"}}), "options.sample_rate", 22);
    requireError(gaitWith({{22, "  sample_rate: 1e6"}}), "options.sample_rate", 22);
    requireError(gaitWith({{22, "  friction_coefficient: -0.5"}}), "options.friction_coefficient",
                 22);
    requireError(gaitWith({{22, "  f_min: 0"}}), "options.f_min", 22);
    requireError(gaitWith({{22, "  ds_alphadot_max: 0"}}), "options.ds_alphadot_max", 22);
    requireError(gaitWith({{22, "  angle_margin: -1e-3"}}), "options.angle_margin", 22);
    requireError(gaitWith({{22, "  friction_smoothing: 0"}}), "options.friction_smoothing", 22);
    // Documented upper bounds: 1e307 passed "> 0" and made every step undefined.
    requireError(gaitWith({{22, "  friction_coefficient: 1e307"}}), "options.friction_coefficient",
                 22, "must be in (0, 10], got 1e307");
    requireError(gaitWith({{22, "  clearance_height: 5"}}), "options.clearance_height", 22,
                 "[0, 1] m");
    requireError(gaitWith({{22, "  target_speed: 11"}}), "options.target_speed", 22, "m/s");
    // Booleans only true/false.
    requireError(gaitWith({{23, "  dry_friction: yes"}}), "options.dry_friction", 23,
                 "expected true or false, got 'yes'");
    requireError(gaitWith({{22, "  target_speed: -0.3"}}), "options.target_speed", 22);
  }
  SECTION("missing robot file: reported at the gait file's robot key") {
    requireError(gaitWith({{2, "robot: no_such_robot.yaml"}}), "robot", 2);
    requireError(gaitWith({{2, "robot: " + scratch().dir().string()}}), "robot", 2);
    // A missing key is reported at its mapping: for the root, the line of its first entry.
    requireError(gaitWith({{2, "#"}}), "robot", 3);
  }
  SECTION("errors inside the robot file name the robot file") {
    const std::string robot = scratch().write("name: broken\n", "robot");
    const std::string path = scratch().write(gaitWith({{2, "robot: " + robot}}));
    try {
      loadGaitFile(path);
      FAIL("no ConfigError");
    } catch (const ConfigError& e) {
      CHECK(e.file() == robot);
      CHECK(e.key() == "lengths");
    }
  }
}

TEST_CASE("summary constraint groups: worst Defined value, counts and max_violation", "[gait_io]") {
  // The hand-made step (defined, with level-5 violations) so that violated counts are > 0.
  const GaitFile g = loadGaitFile(kExample);
  const gaitopt::GaitEvaluator ev(g.robot, g.options, g.model_options);
  GaitParameters violating(gaitopt::kNumGaitParameters);
  for (int i = 0; i < gaitopt::kNumGaitParameters; ++i) violating(i) = kExampleValues[i];
  const auto e = ev.evaluate(violating);
  double worst = 0.0;
  int violated = 0;
  for (const auto& group : ev.layout().groups()) {
    if (group.count == 0) continue;  // a group of another gait family (impact landing)
    const auto s = gaitopt::summarizeConstraintGroup(group, e);
    CHECK(s.defined == group.count);  // a defined step: every entry is Defined
    double expected = -INFINITY;
    for (int k = group.offset; k < group.offset + group.count; ++k)
      expected = std::max(expected, e.g[k]);
    CHECK(s.value == expected);
    worst = std::max(worst, expected);
    violated += s.violated;
  }
  CHECK(violated > 0);
  CHECK(gaitopt::maxDefinedViolation(e) == worst);

  // The extension hook adds members after the standard ones, inside the same object.
  const std::string json = gaitopt::gaitSummaryJson(
      ev, g.parameters, e, [](gaitopt::JsonWriter& w) { w.key("solver").value("none"); });
  CHECK_THAT(json, Contains("\"solver\": \"none\"\n}"));
}

TEST_CASE("gait files in degrees and nonsense angle margins are refused", "[gait_io]") {
  requireError(gaitWith({{5, "  delta1_iDS: -148.6"}}), "parameters.delta1_iDS", 5,
               "an angle of -148.6 rad, more than a turn: gait files hold radians");
  requireError(gaitWith({{6, "  theta3_iDS: 87.1"}}), "parameters.theta3_iDS", 6, "degrees?");
  // Rates and slopes are not angles: a large one is the evaluator's to judge.
  REQUIRE_NOTHROW(loadGaitFile(scratch().write(gaitWith({{16, "  delta1s_iSS: 12.0"}}))));
  requireError(gaitWith({{24, "  angle_margin: 1.0"}}), "options.angle_margin", 24,
               "must be in [0, 0.1] rad, got 1.0");
}
