// The readers' resource limits (docs/reliability.md): file size, line length and nesting depth
// of YAML documents, rows and line length of sweep.csv files.
#include <catch2/catch.hpp>

#include <string>

#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/io/yaml_reader.hpp"
#include "gaitopt/io/sweep_file.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

using Catch::Matchers::Contains;

TEST_CASE("bad input: reader resource limits", "[reliability]") {
  using gaitopt::YamlLimits;
  const auto load = gaitopt::loadOptimizeConfig;
  gaitopt::test::ScratchDir dir("reader_limits", "input");
  const std::string robot = gaitopt::test::sourcePath("configs/robot/rabbit_miossec.yaml");
  const auto refused = [&](const std::string& text, const std::string& problem) {
    const std::string path = dir.write("robot: " + robot + "\n" + text);
    CHECK_THROWS_WITH(load(path), Contains(path) && Contains(problem));
  };
  refused("# " + std::string(YamlLimits::kMaxFileBytes, 'x') + "\n", "larger than 1048576 bytes");
  refused("# " + std::string(YamlLimits::kMaxLineBytes, 'x') + "\n", "line longer than 4096");
  refused("options: " + std::string(40, '[') + std::string(40, ']') + "\n",
          "nested deeper than 32 levels");
  refused("options: " + std::string(1500, '[') + std::string(1500, ']') + "\n",
          "nested deeper than 32 levels");
  std::string block = "options:\n";
  for (int depth = 1; depth <= 40; ++depth) block += std::string(2 * depth, ' ') + "a:\n";
  refused(block, "nested deeper than 32 levels");

  // sweep.csv: rows and line length.
  std::string csv = std::string(gaitopt::kSweepCsvHeader) + "\n";
  for (int i = 1; i <= 10001; ++i)
    csv += std::to_string(i * 0.0009) + ",optimal,1,1,1,1,0.3,0.5,0.1,10,0.1\n";
  CHECK_THROWS_WITH(gaitopt::mergeSweepCsvs({csv}, {"big.csv"}),
                    Contains("big.csv:10002: more than 10000 rows (limit)"));
  CHECK_THROWS_WITH(
      gaitopt::mergeSweepCsvs({std::string(gaitopt::kSweepCsvHeader) + "\n" +
                               std::string(5000, '1') + "\n"},
                              {"long.csv"}),
      Contains("long.csv:2: line longer than 4096 bytes"));
}
