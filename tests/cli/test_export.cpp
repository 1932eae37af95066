// `gaitopt export`: the CSV (metadata with the robot file's digest, schema and rotor model)
// and the JSON document written and read back; a bad step count or rotor model exits 2 with
// nothing written.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <filesystem>

#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/io/controller_export_file.hpp"
#include "gaitopt/io/file_digest.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

TEST_CASE("gaitopt export CLI: CSV and JSON, bad input", "[export]") {
  ScratchDir dir("export");
  const std::string gait = sourcePath("configs/gait/default_step.yaml");
  const std::string csv = dir.fresh("walk") + ".csv";
  CliRun run = runCli("export --gait " + quoted(gait) + " --steps 2 --rate 250 --out " +
                      quoted(csv));
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  const ExportCsvFile back = readExportCsv(csv);
  CHECK(back.meta.at("steps") == "2");
  CHECK(back.meta.at("schema_version") == "2");
  CHECK(back.meta.at("rotor_model") == "exact");
  CHECK(back.meta.at("robot_sha256") ==
        fileSha256(sourcePath("configs/robot/rabbit_miossec.yaml")));
  CHECK(back.rows.back().step == 1);
  const std::string json = dir.fresh("walk") + ".json";
  run = runCli("export --gait " + quoted(gait) + " --format json --rate 250 --rotor high_gear "
               "--out " + quoted(json));
  REQUIRE(run.exit_code == 0);
  CHECK_THAT(run.out, Catch::Matchers::Contains("rotor high_gear"));
  const ControllerExport back_json = readControllerExport(json);
  CHECK(back_json.gait.robot_path == loadGaitFile(gait).robot_path);
  CHECK(back_json.rotor == RotorModel::HighGear);
  const std::string bad_rotor = dir.fresh("bad") + ".csv";
  run = runCli("export --gait " + quoted(gait) + " --rotor armature --out " + quoted(bad_rotor));
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Matchers::Contains("--rotor"));
  CHECK_FALSE(std::filesystem::exists(bad_rotor));
  for (const std::string& args : std::vector<std::string>{"--format json",
                                                         "--format json --gait " + quoted(gait),
                                                         "--ramp"}) {
    const std::string bad_library = dir.fresh("bad") + ".json";
    run = runCli("export --library " + quoted(dir.dir().string()) + " " + args + " --out " +
                 quoted(bad_library));
    INFO(args);
    CHECK(run.exit_code == 2);
    CHECK_FALSE(std::filesystem::exists(bad_library));
  }
  const std::string bad = dir.fresh("bad") + ".csv";
  run = runCli("export --gait " + quoted(gait) + " --steps 0 --out " + quoted(bad));
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Matchers::Contains("--steps"));
  CHECK_FALSE(std::filesystem::exists(bad));
}

}  // namespace gaitopt::test
