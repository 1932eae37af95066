#include "gaitopt/math/decimal.hpp"

#include <cstdio>

namespace gaitopt {

std::string formatDouble(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace gaitopt
