// Command-line overrides of configuration and gait files (io/overrides.hpp): applied to the
// document before it is read, validated like the file, errors naming the override.
#include <catch2/catch.hpp>

#include <filesystem>

#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/io/overrides.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

using namespace gaitopt;
using Catch::Matchers::Contains;

namespace {

// `read` must throw a ConfigError whose message starts with `start` and contains `problem`.
template <class Read>
void requireOverrideError(Read&& read, const std::string& start, const std::string& problem) {
  try {
    read();
    FAIL("no ConfigError; expected " << start);
  } catch (const ConfigError& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).rfind(start, 0) == 0);
    CHECK_THAT(std::string(e.what()), Contains(problem));
  }
}

std::string defaultConfig() { return test::sourcePath("configs/default.yaml"); }

}  // namespace

TEST_CASE("parseOverride: KEY=VALUE with a dotted key", "[overrides]") {
  const Override o = parseOverride("options.friction_coefficient=0.7");
  CHECK(o.key == "options.friction_coefficient");
  CHECK(o.value == "0.7");
  CHECK(o.text() == "options.friction_coefficient=0.7");
  CHECK(parseOverride("parameterisation={ss_points: 3}").value == "{ss_points: 3}");
  CHECK(parseOverride("a=b=c").value == "b=c");  // the first '=' splits
  for (const std::string bad : {"", "speed", "speed=", "=0.5", "options..x=1", ".a=1", "a b=1"})
    requireOverrideError([&] { parseOverride(bad); }, "--set: expected KEY=VALUE", bad);
}

TEST_CASE("loadOptimizeConfigWithOverrides: overrides replace and add values, recorded in order",
          "[overrides]") {
  const OptimizeConfig plain = loadOptimizeConfig(defaultConfig());
  REQUIRE(plain.speed == Approx(0.5));
  REQUIRE(plain.options.ss_nodes == 32);
  const OptimizeConfig c = loadOptimizeConfigWithOverrides(
      defaultConfig(), {parseOverride("speed=0.65"), parseOverride("options.ss_nodes=24"),
                        parseOverride("solver.max_iter=7"), parseOverride("speed=0.7")});
  CHECK(*c.speed == 0.7);  // the later override of a key wins
  CHECK(c.options.target_speed == 0.7);
  CHECK(c.options.ss_nodes == 24);
  CHECK(c.options.friction_coefficient == plain.options.friction_coefficient);  // untouched
  CHECK(c.solver.max_iter == 7);
  CHECK(c.overrides ==
        std::vector<std::string>{"speed=0.65", "options.ss_nodes=24", "solver.max_iter=7",
                                 "speed=0.7"});
  CHECK(plain.overrides.empty());
}

TEST_CASE("loadOptimizeConfigWithOverrides: an override adds a mapping the file does not have",
          "[overrides]") {
  test::ScratchDir dir("overrides");
  const std::string robot = test::sourcePath("configs/robot/rabbit_miossec.yaml");
  const std::string config = dir.write("robot: " + robot + "\nspeed: 0.5\n");
  const OptimizeConfig c =
      loadOptimizeConfigWithOverrides(config, {parseOverride("options.min_normal_force=35")});
  CHECK(c.options.min_normal_force == 35.0);
}

TEST_CASE("loadOptimizeConfigWithOverrides: an override is validated like the file and named in errors",
          "[overrides]") {
  const std::string file = defaultConfig();
  const auto load = [&](const std::string& o) {
    return [file, o] { loadOptimizeConfigWithOverrides(file, {parseOverride(o)}); };
  };
  requireOverrideError(load("options.friction_coefficient=abc"),
                       "--set options.friction_coefficient=abc: key 'options.friction_coefficient'",
                       "expected a number");
  requireOverrideError(load("options.frobnicate=1"), "--set options.frobnicate=1: key "
                       "'options.frobnicate'", "unknown key (expected one of:");
  requireOverrideError(load("speed=-1"), "--set speed=-1: key 'speed'", "must be > 0");
  requireOverrideError(load("speed.x=1"), "--set speed.x=1: key 'speed.x'",
                       "'speed' does not hold a mapping");
  requireOverrideError(load("options.ss_nodes=[1, 2"), "--set options.ss_nodes=[1, 2",
                       "invalid YAML");
  // An error elsewhere in the file still names the file: a mapping added inside `solver`
  // leaves `solver.backend`'s own line.
  requireOverrideError(load("solver.ipopt={print_level: 5}"),
                       "--set solver.ipopt={print_level: 5}: key 'solver.ipopt'", "");
}

TEST_CASE("the unknown-key message lists every option a gait file may set", "[overrides]") {
  try {
    loadOptimizeConfigWithOverrides(defaultConfig(), {parseOverride("options.frobnicate=1")});
    FAIL("no error");
  } catch (const ConfigError& e) {
    for (const char* key : {"dry_friction", "ds_distribution", "full_torque_envelope", "rotor",
                            "landing", "after_impact", "touchdown_speed_min", "ss_nodes"})
      CHECK_THAT(std::string(e.what()), Contains(std::string(key)));
  }
}

TEST_CASE("loadGaitFileWithOverrides: --robot and option overrides, the robot path kept absolute",
          "[overrides]") {
  const std::string gait = test::sourcePath("configs/gait/default_step.yaml");
  const std::string robot = test::sourcePath("configs/robot/rabbit_chesse.yaml");
  const GaitFile g = loadGaitFileWithOverrides(
      gait, {{"robot", robot}, parseOverride("options.target_speed=0.45")});
  CHECK(g.robot_path == std::filesystem::path(robot).lexically_normal().string());
  CHECK(g.robot.name == loadRobot(robot).name);
  CHECK(g.options.target_speed == 0.45);
  CHECK(g.parameters == loadGaitFile(gait).parameters);
  CHECK(g.overrides.size() == 2);
  requireOverrideError([&] { loadGaitFileWithOverrides(gait, {parseOverride("parameters.d=-1")}); },
                       "--set parameters.d=-1: key 'parameters.d'", "");
}
