#pragma once
// Root of a continuous function on a bracket where it changes sign, without derivatives.
#include <cmath>

namespace gaitopt {

// x in [lo, hi] (lo < hi) where fn changes sign, given f_lo = fn(lo) and f_hi = fn(hi) of
// opposite signs: Illinois-modified regula falsi (superlinear, never leaves the bracket), to
// 1e-12 in x. A non-finite value of fn stops it at the bracket's middle.
template <class F>
double bracketedRoot(const F& fn, double lo, double f_lo, double hi, double f_hi) {
  int side = 0;
  for (int it = 0; it < 80 && hi - lo > 1e-12; ++it) {
    double t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);  // secant unusable (huge or equal values)
    const double ft = fn(t);
    if (!std::isfinite(ft)) return 0.5 * (lo + hi);
    if (ft == 0.0) return t;
    if ((ft < 0.0) == (f_lo < 0.0)) {
      lo = t;
      f_lo = ft;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = t;
      f_hi = ft;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace gaitopt
