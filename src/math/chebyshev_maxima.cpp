#include "gaitopt/math/chebyshev_maxima.hpp"

#include <algorithm>
#include <cmath>

namespace gaitopt {
namespace {

// Sub-intervals per interval: the interpolant of degree n has at most one or two extrema
// between neighbouring nodes, so the sample brackets the maximum for Newton.
constexpr int kSamples = 6;
constexpr int kNewtonSteps = 8;

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

IntervalMaxima::IntervalMaxima(const ChebyshevGrid& grid) : grid_(grid) {
  const int per = kSamples - 1;
  sample_s_.resize(grid.degree() * per);
  sample_.resize(sample_s_.size(), grid.size());
  for (int k = 0; k < grid.degree(); ++k)
    for (int i = 0; i < per; ++i) {
      const double lo = grid.nodes()[k + 1], hi = grid.nodes()[k];
      const int row = k * per + i;
      sample_s_[row] = lo + (hi - lo) * (i + 1) / kSamples;
      sample_.row(row) = lagrangeBasis(grid, sample_s_[row]).transpose();
    }
}

std::vector<InterpolantMaximum> IntervalMaxima::operator()(const Eigen::VectorXd& values) const {
  const Eigen::VectorXd& x = grid_.nodes();
  const Eigen::VectorXd samples = sample_ * values;
  const Eigen::VectorXd slope = grid_.differentiation() * values;  // nodal G'
  std::vector<InterpolantMaximum> out;
  const int per = kSamples - 1;
  for (int k = 0; k < grid_.degree(); ++k) {
    const double lo = x[k + 1], hi = x[k];
    // The higher node, and whether G rises from it into the interval (then the maximum is
    // inside even when no sample shows it).
    const bool high = values[k] >= values[k + 1];
    InterpolantMaximum best = high ? InterpolantMaximum{hi, values[k]}
                                   : InterpolantMaximum{lo, values[k + 1]};
    bool inside = high ? slope[k] < 0.0 : slope[k + 1] > 0.0;
    for (int i = 0; i < per; ++i)
      if (samples[k * per + i] > best.value) {
        best = {sample_s_[k * per + i], samples[k * per + i]};
        inside = true;
      }
    if (inside) best = refine(values, slope, best, lo, hi);
    out.push_back(best);
  }
  return out;
}

// Newton on G'(s) = 0 from `start`, kept in [lo, hi]; the better of start and result.
InterpolantMaximum IntervalMaxima::refine(const Eigen::VectorXd& values,
                                          const Eigen::VectorXd& slope, InterpolantMaximum start,
                                          double lo, double hi) const {
  double s = start.s;
  for (int it = 0; it < kNewtonSteps; ++it) {
    const auto [d1, d2] = grid_.interpolateWithDerivative(slope, s);
    if (!(d2 < 0.0)) break;
    const double next = std::clamp(s - d1 / d2, lo, hi);
    const bool done = std::abs(next - s) < 1e-14;
    s = next;
    if (done) break;
  }
  const double v = grid_.interpolate(values, s);
  return v > start.value ? InterpolantMaximum{s, v} : start;
}

}  // namespace gaitopt
