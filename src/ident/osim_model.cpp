#include "gaitopt/ident/osim_model.hpp"

#include <algorithm>

#include "gaitopt/math/fmm_spline.hpp"

namespace gaitopt {
namespace {

double piecewiseLinearValue(const std::vector<double>& x, const std::vector<double>& y, double q) {
  const std::size_t n = x.size();
  const std::size_t k = q <= x[0] ? 0
                        : q >= x[n - 1]
                            ? n - 2
                            : static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), q) - x.begin()) - 1;
  return y[k] + (q - x[k]) * (y[k + 1] - y[k]) / (x[k + 1] - x[k]);
}

}  // namespace

double osimFunctionValue(const OsimFunction& f, double q) {
  switch (f.kind) {
    case OsimFunction::Kind::Constant: return f.y[0];
    case OsimFunction::Kind::Linear: return f.y[0] * q + f.y[1];
    case OsimFunction::Kind::SimmSpline: return fmmSplineValue(f.x, f.y, q);
    case OsimFunction::Kind::PiecewiseLinear: return piecewiseLinearValue(f.x, f.y, q);
    case OsimFunction::Kind::Polynomial: {
      double v = 0.0;
      for (const double c : f.y) v = v * q + c;  // Horner, highest power first
      return v;
    }
    case OsimFunction::Kind::Multiplier: return f.scale * osimFunctionValue(f.inner.front(), q);
  }
  return 0.0;
}

}  // namespace gaitopt
