#include "gaitopt/io/csv_table.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/math/decimal.hpp"

namespace gaitopt {

std::vector<std::string> splitFields(const std::string& line, char separator) {
  std::vector<std::string> fields;
  if (line.empty()) return fields;
  std::string::size_type begin = 0;
  while (true) {
    const auto end = line.find(separator, begin);
    fields.push_back(line.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
    if (end == std::string::npos) break;
    begin = end + 1;
  }
  return fields;
}

std::optional<double> parseDecimal(const std::string& field) {
  if (field.empty() || field.size() > 64 ||
      field.find_first_not_of("0123456789+-.eE") != std::string::npos)
    return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(field.c_str(), &end);
  if (end != field.c_str() + field.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::string decimalProblem(const std::string& field) {
  if (parseDecimal(field)) return "";
  if (field.empty()) return "empty value";
  const std::string quoted = "'" + printable(field) + "'";
  // strtod reads hex, blanks, inf and nan too: a finite value there is a refused spelling.
  char* end = nullptr;
  const double v = std::strtod(field.c_str(), &end);
  if (end == field.c_str() + field.size() && std::isfinite(v))
    return "not a decimal number: " + quoted + " (digits, sign, point and exponent only)";
  return "not a finite number: " + quoted;
}

double parseCsvNumber(const std::string& field, const std::string& file,
                      const std::string& column, int line) {
  if (const std::optional<double> v = parseDecimal(field)) return *v;
  throw ConfigError(file, column, line, decimalProblem(field));
}

std::optional<double> finiteOrAbsent(double v) {
  return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
}

CsvRow& CsvRow::text(const std::string& field) {
  if (!first_) line_ += kCsvSeparator;
  first_ = false;
  line_ += field;
  return *this;
}

CsvRow& CsvRow::integer(long long v) { return text(std::to_string(v)); }

CsvRow& CsvRow::number(double v) { return text(formatDouble(v)); }

CsvRow& CsvRow::number(double v, const char* printf_format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, v);
  return text(buf);
}

CsvRow& CsvRow::number(const std::optional<double>& v) { return v ? number(*v) : empty(); }

CsvRow& CsvRow::texts(const std::vector<std::string>& fields) {
  for (const std::string& f : fields) text(f);
  return *this;
}

std::string csvHeader(std::initializer_list<const char*> names) {
  CsvRow row;
  for (const char* name : names) row.text(name);
  return row.line();
}

}  // namespace gaitopt
