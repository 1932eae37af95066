#pragma once
// Decimal text of a double that reads back to the same double (17 significant digits), for
// files and messages alike, so a number printed anywhere in gaitopt can be typed back exactly.
#include <string>

namespace gaitopt {

std::string formatDouble(double v);

}  // namespace gaitopt
