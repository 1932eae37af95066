// The CSV row writer: the separator, the number formats and the empty field of an absent value,
// read back by the project's CSV reader.
#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <string>

#include "gaitopt/io/csv_table.hpp"

namespace gaitopt {

TEST_CASE("csv row: fields, numbers that read back exactly, empty absent values", "[io]") {
  CsvRow row;
  row.number(0.1).integer(-3).text("SS").number(std::nullopt).number(finiteOrAbsent(std::nan("")));
  row.numbers(Eigen::Vector2d(1.5, -2.0)).number(1.0 / 3.0, "%.10g");
  CHECK(row.line() == "0.10000000000000001,-3,SS,,,1.5,-2,0.3333333333\n");
  const std::vector<std::string> f = splitFields(row.str());
  REQUIRE(f.size() == 8);
  CHECK(parseDecimal(f[0]) == 0.1);
  CHECK(csvHeader({"t", "phase"}) == "t,phase\n");
  CHECK(CsvRow().line() == "\n");
}

}  // namespace gaitopt
