// Reading a JSON controller export back: the embedded gait rebuilt bit for bit, and each
// rejection (not an export, unknown schema, missing or malformed embedded file) with its message.
#include <catch2/catch.hpp>

#include <fstream>

#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/io/controller_export_file.hpp"
#include "test_default_gait.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

namespace gaitopt::test {
namespace {

std::string exportJsonText(const ShippedGait& f, RotorModel rotor) {
  ExportRequest req;
  req.steps = 2;
  req.rate = 200;
  ModelOptions options = f.gait.model_options;
  options.rotor = rotor;
  const Model model = buildModel(f.gait.robot, options);
  return exportJson(f.gait, model, f.evaluation, exportMetadata(f.gait, f.evaluation, req),
                    exportTrajectory(f.evaluator, f.evaluation, model, req));
}

std::string written(const std::string& text, const std::string& name) {
  static ScratchDir dir("controller_export_file");
  const std::string path = dir.fresh(name) + ".json";
  std::ofstream(path) << text;
  return path;
}

// 1-based line of the first occurrence of `needle` in `text`.
int lineOf(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  REQUIRE(at != std::string::npos);
  return static_cast<int>(std::count(text.begin(), text.begin() + at, '\n')) + 1;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

const auto read = [](const std::string& p) { readControllerExport(p); };

// The export at `path` refused for its embedded gait file: the message names the JSON file
// with "[gait.yaml]", `key` inside the embedded text and the problem.
void requireEmbeddedGaitError(const std::string& path, const std::string& key,
                              const std::string& problem) {
  try {
    readControllerExport(path);
    FAIL("no ConfigError");
  } catch (const ConfigError& e) {
    CHECK(e.file() == path + " [gait.yaml]");
    CHECK(e.key() == key);
    CHECK_THAT(std::string(e.what()), Catch::Matchers::Contains(problem));
  }
}

}  // namespace

TEST_CASE("Controller export JSON read back rebuilds the exact gait", "[export][io]") {
  for (const char* shipped : {"configs/gait/default_step.yaml",
                              "configs/gait/chevallereau_aoustin_0.75_impact.yaml"}) {
    INFO(shipped);
    const ShippedGait f(shipped);
    REQUIRE(f.evaluation.motion_computed);
    const std::string path = written(exportJsonText(f, RotorModel::HighGear), "round_trip");
    const ControllerExport back = readControllerExport(path);
    CHECK(back.path == path);
    CHECK(back.schema_version == 2);
    CHECK(back.gait.path == path);
    CHECK(back.gait.robot_path == f.gait.robot_path);
    CHECK(back.rotor == RotorModel::HighGear);
    REQUIRE(back.gait.parameters.size() == f.gait.parameters.size());
    for (int i = 0; i < f.gait.parameters.size(); ++i)
      CHECK(back.gait.parameters(i) == f.gait.parameters(i));  // bit for bit
    CHECK(back.gait.options.parameterisation.names() == f.gait.options.parameterisation.names());
    CHECK(back.gait.model_options.rotor == f.gait.model_options.rotor);
    CHECK(back.gait.robot.name == f.gait.robot.name);
    CHECK(back.gait.robot.gear_ratio == f.gait.robot.gear_ratio);
    const GaitEvaluator evaluator(back.gait.robot, back.gait.options, back.gait.model_options);
    const GaitEvaluation<double> e = evaluator.evaluate(back.gait.parameters);
    CHECK(e.speed == f.evaluation.speed);
    CHECK(back.speed == f.evaluation.speed);
    CHECK(back.step_length == f.evaluation.motion.d);
    CHECK(back.t_ss == f.evaluation.motion.T_SS);
    CHECK(back.t_ds == f.evaluation.motion.T_DS);
  }
}

TEST_CASE("Controller export reader rejects what is not a readable export", "[export][io]") {
  const DefaultGait f;
  const std::string text = exportJsonText(f, RotorModel::Exact);
  SECTION("not an export") {
    const std::string path = written("{\n  \"alpha\": [1, 2]\n}\n", "not_export");
    requireConfigError(read, path, "format", 1, "not a gaitopt controller export");
  }
  SECTION("a CSV export") {
    ScratchDir dir("controller_export_file");
    const std::string path = dir.fresh("walk") + ".csv";
    ExportRequest req;
    req.rate = 50;
    std::ofstream(path) << exportCsv(exportMetadata(f.gait, f.evaluation, req),
                                     exportTrajectory(f.evaluator, f.evaluation, f.model, req));
    CHECK_THROWS_AS(readControllerExport(path), ConfigError);
  }
  SECTION("unknown schema version") {
    const std::string bad = replaced(text, "\"schema_version\": 2", "\"schema_version\": 3");
    requireConfigError(read, written(bad, "schema3"), "schema_version",
                       lineOf(bad, "schema_version"), "schema version 3 is not supported");
  }
  SECTION("schema 1") {
    const std::string bad = replaced(text, "\"gaitopt controller export\"",
                                     "\"gaitopt controller export 1\"");
    requireConfigError(read, written(bad, "schema1"), "format", lineOf(bad, "\"format\""),
                       "schema version 1 is not supported");
  }
  SECTION("missing embedded gait") {
    const std::string bad = replaced(text, "\"gait\": {", "\"gait_source\": {");
    // A key missing from the document is reported at the line of its opening brace.
    requireConfigError(read, written(bad, "no_gait"), "gait", 1, "required key is missing");
  }
  SECTION("missing embedded robot text") {
    const std::size_t robot = text.find("\"robot\": {");
    const std::size_t yaml = text.find("\"yaml\":", robot);
    const std::string bad = text.substr(0, yaml) + "\"yml\":" + text.substr(yaml + 7);
    requireConfigError(read, written(bad, "no_robot"), "robot.yaml", lineOf(bad, "\"robot\": {"),
                       "required key is missing");
  }
  SECTION("malformed embedded gait YAML") {
    const std::string bad = replaced(text, "\\nparameters:\\n", "\\nparameters: [\\n");
    requireEmbeddedGaitError(written(bad, "bad_yaml"), "", "invalid YAML");
  }
  SECTION("embedded text not a string") {
    const std::size_t robot = text.find("\"robot\": {");
    const std::size_t yaml = text.find("\"yaml\": \"", robot);
    const std::string bad = text.substr(0, yaml) + "\"yaml\": [7], \"unused\": " +
                            text.substr(yaml + 8);
    requireConfigError(read, written(bad, "robot_text"), "robot.yaml", lineOf(bad, "\"yaml\": [7]"),
                       "expected a string");
  }
  SECTION("bad value in the embedded gait") {
    const std::string bad = replaced(text, "\\n  T_DS: ", "\\n  T_DS: -");
    requireEmbeddedGaitError(written(bad, "bad_value"), "parameters.T_DS", "must be > 0");
  }
}

}  // namespace gaitopt::test
