// The readers' resource limits (docs/reliability.md): file size, line length, nesting depth
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
#include "gaitopt/io/robot_file.hpp"
#include "gaitopt/math/decimal.hpp"
#include "gaitopt/io/yaml_reader.hpp"
#include "gaitopt/io/sweep_file.hpp"
#include "test_files.hpp"
#include "test_opensim_data.hpp"
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
    csv += std::to_string(i * 0.0009) + ",optimal,1,1,1,1,0.002,0.3,0.5,0.1,10,0.1,,,,,\n";
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

TEST_CASE("bad input: table cells are decimal numbers, a byte order mark is accepted",
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

TEST_CASE("bad input: implausible measured data is refused at its row and column",
          "[reliability]") {
  gaitopt::test::ScratchDir dir("reader_plausible", "input");
  const std::vector<std::string> seed =
      gaitopt::test::fileLines(gaitopt::test::sourcePath("fuzz/seeds/measured.csv"));
  // The seed with the cell of `column` (0-based) of data row `row` (1-based) replaced.
  const auto withCell = [&](std::vector<std::string> lines, int row, int column,
                            const std::string& value) {
    std::vector<std::string> cells = gaitopt::splitFields(lines[row]);
    cells[column] = value;
    std::string line;
    for (const std::string& c : cells) line += (line.empty() ? "" : ",") + c;
    lines[row] = line;
    return lines;
  };
  const auto write = [&](const std::vector<std::string>& lines) {
    const std::string path = dir.fresh("data") + ".csv";
    std::ofstream out(path);
    for (const std::string& l : lines) out << l << "\n";
    return path;
  };
  const auto refused = [&](const std::vector<std::string>& lines, const std::string& problem) {
    const std::string path = write(lines);
    CHECK_THROWS_WITH(gaitopt::readMeasuredCsv(path), Contains(path + ":") && Contains(problem));
  };
  refused(withCell(seed, 7, 1, "1e6"),
          ":8: row 7, column 'alpha': angle 1e6 rad is beyond two turns");
  refused(withCell(seed, 30, 4, "-400"), "row 30, column 'delta3': angle -400 rad");
  // One hour inside step 1 (rows 21 to 40), the rest of the file shifted with it.
  std::vector<std::string> gap = seed;
  for (int row = 25; row < static_cast<int>(gap.size()); ++row) {
    const double t = std::stod(gaitopt::splitFields(gap[row])[0]) + 3600.0;
    gap = withCell(gap, row, 0, gaitopt::formatDouble(t));
  }
  refused(gap, ":26: row 25, column 't': gap of 3600.");
  refused(gap, "inside step 1, over 10 times the median sample interval (0.01");
  // The same hour between steps 1 and 2 is accepted.
  std::vector<std::string> between = seed;
  for (int row = 41; row < static_cast<int>(between.size()); ++row) {
    const double t = std::stod(gaitopt::splitFields(between[row])[0]) + 3600.0;
    between = withCell(between, row, 0, gaitopt::formatDouble(t));
  }
  CHECK_NOTHROW(gaitopt::readMeasuredCsv(write(between)));

  // Torques far beyond the robot's envelope (140 N m): refused for diagnose.
  const gaitopt::RobotParams robot =
      gaitopt::loadRobot(gaitopt::test::sourcePath("configs/robot/rabbit_miossec.yaml"));
  const std::string huge = write(withCell(seed, 12, 10, "1e30"));
  const gaitopt::MeasuredData data = gaitopt::readMeasuredCsv(huge);
  CHECK_THROWS_WITH(gaitopt::requirePlausibleTorques(data, robot, huge),
                    Contains(huge + ": column 'gamma2', sample 12 (t = 0.11 s): 1e+30 N m is "
                                    "beyond 10 times the robot's largest envelope torque (140 N m)"));
  CHECK_NOTHROW(gaitopt::requirePlausibleTorques(
      gaitopt::readMeasuredCsv(write(withCell(seed, 12, 10, "1399"))), robot, huge));

  // More rows than the limit: refused at the first one over it.
  std::vector<std::string> many{seed[0]};
  for (std::size_t k = 0; k <= gaitopt::kMaxMeasuredRows; ++k)
    many.push_back(std::to_string(k * 0.001) + ",0,0,0,0,0,SS,left," + std::to_string(k / 50) +
                   ",0,0,0,0,0,300,0,0");
  refused(many, ":100002: row 100001, column '': more than 100000 samples (limit)");
}
