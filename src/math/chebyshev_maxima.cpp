#include "gaitopt/math/chebyshev_maxima.hpp"

#include <algorithm>
#include <cmath>

namespace gaitopt {
namespace {

// Samples per interval before the Newton refinement: the interpolant of degree n has at most
// one or two extrema between neighbouring nodes, so a few points bracket the maximum.
constexpr int kSamples = 6;
constexpr int kNewtonSteps = 6;

}  // namespace

Eigen::VectorXd lagrangeBasis(const ChebyshevGrid& grid, double s) {
  const Eigen::VectorXd& x = grid.nodes();
  Eigen::VectorXd l = Eigen::VectorXd::Zero(grid.size());
  const int j = grid.nearestNode(s);
  if (s == x[j]) {
    l[j] = 1.0;
    return l;
  }
  for (int k = 0; k < grid.size(); ++k) l[k] = grid.barycentricWeights()[k] / (s - x[k]);
  return l / l.sum();
}

std::vector<InterpolantMaximum> intervalMaxima(const ChebyshevGrid& grid,
                                               const Eigen::VectorXd& values) {
  const Eigen::VectorXd& x = grid.nodes();
  const Eigen::VectorXd slope = grid.differentiation() * values;  // nodal G'
  std::vector<InterpolantMaximum> out;
  for (int k = 0; k < grid.degree(); ++k) {
    const double lo = x[k + 1], hi = x[k];
    InterpolantMaximum best{hi, values[k]};
    if (values[k + 1] > best.value) best = {lo, values[k + 1]};
    double start = lo;
    double start_value = -INFINITY;
    for (int i = 1; i < kSamples; ++i) {
      const double s = lo + (hi - lo) * i / kSamples;
      const double v = grid.interpolate(values, s);
      if (v > start_value) start = s, start_value = v;
    }
    // Newton on G'(s) = 0 from the best interior sample, kept inside the interval.
    double s = start;
    for (int it = 0; it < kNewtonSteps; ++it) {
      const auto [d1, d2] = grid.interpolateWithDerivative(slope, s);
      if (!(d2 < 0.0)) break;
      s = std::clamp(s - d1 / d2, lo, hi);
    }
    for (const double c : {start, s}) {
      const double v = grid.interpolate(values, c);
      if (v > best.value) best = {c, v};
    }
    out.push_back(best);
  }
  return out;
}

}  // namespace gaitopt
