// The readers' resource limits (README, "Input limits"): file size, line length, nesting depth
// and alias expansion of YAML documents, rows and line length of sweep.csv files; regular files
// only; the one number syntax of tables and measured data.
#include <catch2/catch.hpp>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/input_file.hpp"
#include "gaitopt/io/measured_data.hpp"
#include "gaitopt/io/opensim_table.hpp"
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

TEST_CASE("bad input: YAML alias bombs are refused at the alias budget", "[reliability]") {
  // 9 levels of 10 aliases: 10^9 nodes once expanded, from about 500 bytes.
  std::string bomb = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int level = 1; level <= 9; ++level) {
    const std::string prev = "*a" + std::to_string(level - 1);
    bomb += "a" + std::to_string(level) + ": &a" + std::to_string(level) + " [";
    for (int k = 0; k < 10; ++k) bomb += (k ? ", " : "") + prev;
    bomb += "]\n";
  }
  CHECK(bomb.size() < 600);
  CHECK_THROWS_WITH(gaitopt::parseYamlText(bomb, "bomb.yaml"),
                    Contains("bomb.yaml: ") && Contains("nodes once aliases are expanded"));
  // A few aliases that stay within the budget are read as before.
  const YAML::Node small = gaitopt::parseYamlText("a: &v [1, 2]\nb: *v\nc: *v\n", "small.yaml");
  CHECK(small["c"][1].as<double>() == 2.0);
}

TEST_CASE("bad input: readers take regular files only", "[reliability]") {
  gaitopt::test::ScratchDir dir("reader_kinds", "input");
  const std::string fifo = dir.fresh("fifo");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);  // no writer: an open without O_NONBLOCK blocks
  const std::string folder = dir.fresh("folder");
  std::filesystem::create_directories(folder);
  const auto refused = [](const std::string& path, const std::string& problem) {
    CHECK_THROWS_WITH(gaitopt::readInputFile(path, 1024, "1 KiB"),
                      Contains(path + ": " + problem));
    CHECK_THROWS_WITH(gaitopt::loadOptimizeConfig(path), Contains(path + ": " + problem));
    CHECK_THROWS_WITH(gaitopt::readMeasuredCsv(path), Contains(path + ": " + problem));
    CHECK_THROWS_WITH(gaitopt::readOpenSimTable(path), Contains(path + ": " + problem));
  };
  refused(fifo, "is a FIFO (named pipe), a regular file is expected");
  refused(folder, "is a directory, a file is expected");
  refused("/dev/zero", "is a device, a regular file is expected");
  refused(dir.fresh("missing"), "no such file");
  const std::string big = dir.fresh("big");
  std::ofstream(big) << std::string(2000, 'x');
  CHECK_THROWS_WITH(gaitopt::readInputFile(big, 1024, "1 KiB"),
                    Contains(big + ": file larger than 1 KiB (limit)"));
}

TEST_CASE("bad input: table cells are decimal numbers; a byte order mark is accepted",
          "[reliability]") {
  using gaitopt::decimalProblem;
  CHECK(gaitopt::parseDecimal("-1.5e-3") == -1.5e-3);
  CHECK(decimalProblem("0x10") == "not a decimal number: '0x10' (digits, sign, point and "
                                  "exponent only)");
  CHECK(decimalProblem("0x1p3").rfind("not a decimal number: '0x1p3'", 0) == 0);
  CHECK(decimalProblem("abc") == "not a finite number: 'abc'");
  CHECK(decimalProblem("nan") == "not a finite number: 'nan'");
  CHECK(decimalProblem("-inf") == "not a finite number: '-inf'");
  CHECK(decimalProblem("1e999") == "not a finite number: '1e999'");
  CHECK(decimalProblem(" 1").rfind("not a decimal number", 0) == 0);
  CHECK(decimalProblem("") == "empty value");
  const std::string longer = decimalProblem(std::string(5000, '7') + "x");
  CHECK(longer.size() < 300);  // the value is quoted by its first 200 bytes

  gaitopt::test::ScratchDir dir("reader_cells", "input");
  const std::string seed = gaitopt::test::readFile(gaitopt::test::sourcePath("fuzz/seeds/measured.csv"));
  const std::string plain = dir.fresh("plain") + ".csv", bom = dir.fresh("bom") + ".csv";
  std::ofstream(plain) << seed;
  std::ofstream(bom) << "\xEF\xBB\xBF" << seed;
  CHECK(gaitopt::measuredCsv(gaitopt::readMeasuredCsv(bom)) ==
        gaitopt::measuredCsv(gaitopt::readMeasuredCsv(plain)));
  std::string hex = seed;
  hex.replace(hex.find("\n0,-0.2,") + 1, 1, "0x0");
  const std::string hex_path = dir.fresh("hex") + ".csv";
  std::ofstream(hex_path) << hex;
  CHECK_THROWS_WITH(gaitopt::readMeasuredCsv(hex_path),
                    Contains(hex_path + ":2: row 1, column 't': not a decimal number: '0x0'"));
}
