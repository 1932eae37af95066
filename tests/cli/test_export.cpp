// `gaitopt export`: the CSV (metadata with the robot file's digest) and the JSON document
// written; a bad step count exits 2 with nothing written.
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
  CHECK(back.meta.at("robot_sha256") ==
        fileSha256(sourcePath("configs/robot/rabbit_miossec.yaml")));
  CHECK(back.rows.back().step == 1);
  const std::string json = dir.fresh("walk") + ".json";
  run = runCli("export --gait " + quoted(gait) + " --format json --rate 250 --out " +
               quoted(json));
  REQUIRE(run.exit_code == 0);
  const ControllerExport back_json = readControllerExport(json);
  CHECK(back_json.gait.robot_path == loadGaitFile(gait).robot_path);
  CHECK(back_json.rotor == RotorModel::Exact);
  const std::string bad = dir.fresh("bad") + ".csv";
  run = runCli("export --gait " + quoted(gait) + " --steps 0 --out " + quoted(bad));
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Matchers::Contains("--steps"));
  CHECK_FALSE(std::filesystem::exists(bad));
}

}  // namespace gaitopt::test
