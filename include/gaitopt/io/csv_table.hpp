#pragma once
// The comma-separated files of the project (sweep.csv, measured data, controller exports) and
// the number lists of the command line: fields split at every separator, no quoting (the
// files hold numbers and plain labels), and numbers parsed whole. Every CSV file is written
// through CsvRow, so the separator and the number format live here.
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

namespace gaitopt {

constexpr char kCsvSeparator = ',';

// Fields of `line` split at every `separator`: "a,,b" gives a, "", b; a trailing separator an
// empty last field; an empty line no field at all.
std::vector<std::string> splitFields(const std::string& line, char separator = kCsvSeparator);

// A decimal number as written in a CSV cell, a table field or on the command line: digits,
// sign, point and exponent only (no blanks, hex, inf or nan), at most 64 characters, finite.
// Empty when it is not one. The one number syntax of every reader and option.
std::optional<double> parseDecimal(const std::string& field);

// Why parseDecimal refuses `field`, for messages ("empty value", "not a finite number: 'abc'",
// "not a decimal number: '0x10' (...)", the field printable and cut at 200 bytes); "" when it
// accepts it.
std::string decimalProblem(const std::string& field);

// parseDecimal, or a ConfigError (file, column as key, line) with decimalProblem.
double parseCsvNumber(const std::string& field, const std::string& file,
                      const std::string& column, int line);

// `v` when finite, absent otherwise: a value that could not be computed is an empty field.
std::optional<double> finiteOrAbsent(double v);

// One line of a CSV file being written: fields joined by kCsvSeparator; numbers through
// formatDouble so that they read back exactly, unless the file's format asks for a printf
// format of fewer digits.
class CsvRow {
 public:
  CsvRow& text(const std::string& field);
  CsvRow& integer(long long v);
  CsvRow& number(double v);
  CsvRow& number(double v, const char* printf_format);
  // An empty field for an absent value.
  CsvRow& number(const std::optional<double>& v);
  CsvRow& empty() { return text(std::string()); }
  CsvRow& texts(const std::vector<std::string>& fields);

  // Every coefficient of a vector (Eigen or any type with size() and operator()).
  template <class Vector>
  CsvRow& numbers(const Vector& v) {
    for (decltype(v.size()) i = 0; i < v.size(); ++i) number(static_cast<double>(v(i)));
    return *this;
  }

  // The row without, and with, its line end.
  const std::string& str() const { return line_; }
  std::string line() const { return line_ + '\n'; }

 private:
  std::string line_;
  bool first_ = true;
};

// The header line (with its line end) naming the columns.
std::string csvHeader(std::initializer_list<const char*> names);

}  // namespace gaitopt
