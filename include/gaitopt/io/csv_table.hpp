#pragma once
// The comma-separated files of the project (sweep.csv, measured data, controller exports) and
// the number lists of the command line: fields split at every separator, no quoting (the
// files hold numbers and plain labels), and numbers parsed whole.
#include <optional>
#include <string>
#include <vector>

namespace gaitopt {

// Fields of `line` split at every `separator`: "a,,b" gives a, "", b; a trailing separator an
// empty last field; an empty line no field at all.
std::vector<std::string> splitFields(const std::string& line, char separator = ',');

// The whole of `field` as a finite number in std::stod's syntax (leading blanks allowed);
// empty otherwise (trailing characters, NaN, inf, out of range).
std::optional<double> parseFiniteNumber(const std::string& field);

// The same, a ConfigError (file, column, line) "not a finite number: '<field>'" otherwise.
double parseCsvNumber(const std::string& field, const std::string& file,
                      const std::string& column, int line);

// A decimal number as written in a strict CSV field or on the command line: digits, sign,
// point and exponent only (no blanks, hex, inf or nan), at most 64 characters, finite. Empty
// when it is not one.
std::optional<double> parseDecimal(const std::string& field);

}  // namespace gaitopt
