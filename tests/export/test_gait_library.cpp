// Gait library over speed (`gaitopt export --library`): the optimal gaits of a sweep output in
// speed order, each with the same phases as its own controller export; a robot that differs
// and a sweep without an optimal speed refused; the CLI.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "gaitopt/export/gait_library.hpp"
#include "gaitopt/io/sweep_file.hpp"
#include "test_export_rows.hpp"
#include "test_files.hpp"

namespace gaitopt::test {
namespace {

// A sweep output as `gaitopt sweep` lays it out: sweep.csv and v<speed>/gait.yaml, the gait
// files those of shipped gaits (robot path absolute), with the status of each speed.
std::string sweepDir(ScratchDir& scratch,
                     const std::vector<std::tuple<double, std::string, ShippedGait*>>& points) {
  const std::filesystem::path dir = scratch.fresh("sweep");
  std::filesystem::create_directories(dir);
  std::ofstream csv(dir / "sweep.csv");
  csv << kSweepCsvHeader << "\n";
  for (const auto& [speed, status, f] : points) {
    csv << speed << "," << status << ",1,1,1,1,0.002,0.3,0.5,0.04,10,1,,,,,\n";
    const std::filesystem::path folder = dir / sweepFolderName(speed, 3);
    std::filesystem::create_directories(folder);
    std::ofstream(folder / "gait.yaml") << gaitYaml(f->gait.robot_path, f->gait.parameters,
                                                    f->gait.options, f->gait.model_options);
  }
  return dir.string();
}

}  // namespace

TEST_CASE("Gait library: the optimal gaits of a sweep with their export phases", "[export]") {
  ShippedGait slow("configs/gait/optimal_0.3.yaml"), medium("configs/gait/default_step.yaml"),
      fast("configs/gait/optimal_0.8.yaml");
  ScratchDir scratch("library");
  const std::string dir = sweepDir(
      scratch, {{0.3, "optimal", &slow}, {0.5, "optimal", &medium}, {0.8, "max_iter", &fast}});
  const std::vector<LibraryGait> gaits = loadSweepGaits(dir);
  REQUIRE(gaits.size() == 2);
  CHECK(gaits[0].speed == 0.3);
  CHECK(gaits[1].folder == "v0.500");
  const YAML::Node doc = YAML::Load(gaitLibraryJson(gaits, RotorModel::HighGear));
  CHECK(doc["format"].as<std::string>() == "gaitopt gait library");
  CHECK(doc["schema_version"].as<int>() == 2);
  CHECK(doc["feedforward"]["rotor_model"].as<std::string>() == "high_gear");
  CHECK(doc["robot"]["yaml"].as<std::string>() == readFile(medium.gait.robot_path));
  REQUIRE(doc["gaits"].size() == 2);
  const ShippedGait* shipped[] = {&slow, &medium};
  for (std::size_t i = 0; i < 2; ++i) {
    const YAML::Node g = doc["gaits"][i];
    CHECK(g["cyclic_gait"]["speed"].as<double>() == shipped[i]->evaluation.speed);
    CHECK(g["gait"]["yaml"].as<std::string>() == readFile(gaits[i].gait.path));
    // The same virtual constraints as the gait's own controller export.
    const YAML::Node own = exportedJson(*shipped[i], 100).doc["phases"];
    for (const char* name : {"phi_knee_stance", "phi_hip_stance", "phi_hip_swing",
                             "phi_knee_swing"}) {
      const YAML::Node a = g["phases"]["SS"]["outputs"][name]["bezier"];
      const YAML::Node b = own["SS"]["outputs"][name]["bezier"];
      REQUIRE(a.size() == b.size());
      for (std::size_t k = 0; k < a.size(); ++k) CHECK(a[k].as<double>() == b[k].as<double>());
    }
    CHECK(g["phases"]["DS"]["alpha_end"].as<double>() == own["DS"]["alpha_end"].as<double>());
  }
}

TEST_CASE("Gait library refuses a sweep without an optimal speed and mixed robots",
          "[export]") {
  ShippedGait medium("configs/gait/default_step.yaml"),
      other("configs/gait/chesse_0.85_ipopt.yaml");
  ScratchDir scratch("library");
  const std::string none = sweepDir(scratch, {{0.5, "infeasible", &medium}});
  CHECK_THROWS_WITH(loadSweepGaits(none), Catch::Matchers::Contains("no speed is optimal"));
  const std::string mixed =
      sweepDir(scratch, {{0.5, "optimal", &medium}, {0.85, "optimal", &other}});
  const std::vector<LibraryGait> gaits = loadSweepGaits(mixed);
  try {
    gaitLibraryJson(gaits, RotorModel::Exact);
    FAIL("no ConfigError");
  } catch (const ConfigError& e) {
    CHECK(e.file() == gaits[1].gait.path);
    CHECK(e.key() == "robot");
    CHECK_THAT(std::string(e.what()), Catch::Matchers::Contains("differs"));
  }
  const std::string out = scratch.fresh("library") + ".json";
  CliRun run = runCli("export --library " + quoted(mixed) + " --format json --out " + quoted(out));
  CHECK(run.exit_code == 2);
  CHECK_FALSE(std::filesystem::exists(out));
}

}  // namespace gaitopt::test
