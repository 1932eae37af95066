#include "gaitopt/model/support_bar.hpp"

namespace gaitopt {

TrunkParameters trunkWithBar(double m3, double s3, double I3, double equivalent_mass) {
  TrunkParameters t;
  t.mass = m3 + equivalent_mass;                                        // (1.24)
  t.com_offset = s3 * m3 / t.mass;                                      // (1.24)
  t.inertia = I3 + m3 * s3 * s3 - t.mass * t.com_offset * t.com_offset; // (1.24)
  return t;
}

double barEquivalentMass(double bar_length, double overhang, double bar_mass,
                         double counterweight_mass) {
  const double l_G = 0.5 * bar_length;
  return (bar_mass * l_G - counterweight_mass * overhang) / (bar_length - overhang);  // (1.29)
}

}  // namespace gaitopt
