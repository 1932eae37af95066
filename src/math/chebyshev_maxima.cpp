#include "gaitopt/math/chebyshev_maxima.hpp"

#include <algorithm>
#include <cmath>

#include "gaitopt/math/degree_cache.hpp"

namespace gaitopt {
namespace {

// Sub-intervals per interval: the interpolant of degree n has at most one or two extrema
// between neighbouring nodes, so the sample brackets the maximum for Newton.
constexpr int kSamples = 6;
constexpr int kNewtonSteps = 8;

// Newton on G'(s) = 0 from `start`, kept in [lo, hi]; the better of start and result.
InterpolantMaximum refine(const ChebyshevGrid& grid, const Eigen::VectorXd& values,
                          const Eigen::VectorXd& slope, InterpolantMaximum start, double lo,
                          double hi) {
  double s = start.s;
  for (int it = 0; it < kNewtonSteps; ++it) {
    const auto [d1, d2] = grid.interpolateWithDerivative(slope, s);
    if (!(d2 < 0.0)) break;
    const double next = std::clamp(s - d1 / d2, lo, hi);
    const bool done = std::abs(next - s) < 1e-14;
    s = next;
    if (done) break;
  }
  const double v = grid.interpolate(values, s);
  return v > start.value ? InterpolantMaximum{s, v} : start;
}

// The ends of [lo, hi] with the interpolant's value and slope there.
struct IntervalEnds {
  double lo, hi, value_lo, value_hi, slope_lo, slope_hi;
};

// The higher end, or the best of the interior samples when one beats it; Newton from there
// when the maximum is inside: a sample beats both ends, or G rises from the higher end inwards.
InterpolantMaximum bestOf(const ChebyshevGrid& grid, const Eigen::VectorXd& values,
                          const Eigen::VectorXd& slope, const IntervalEnds& e,
                          const double* sample_s, const double* sample_value) {
  const bool high = e.value_hi >= e.value_lo;
  InterpolantMaximum best = high ? InterpolantMaximum{e.hi, e.value_hi}
                                 : InterpolantMaximum{e.lo, e.value_lo};
  bool inside = high ? e.slope_hi < 0.0 : e.slope_lo > 0.0;
  for (int i = 0; i < kSamples - 1; ++i)
    if (sample_value[i] > best.value) {
      best = {sample_s[i], sample_value[i]};
      inside = true;
    }
  return inside ? refine(grid, values, slope, best, e.lo, e.hi) : best;
}

}  // namespace

Eigen::VectorXd lagrangeBasis(const ChebyshevGrid& grid, double s) {
  Eigen::VectorXd l;
  lagrangeBasis(grid, s, l);
  return l;
}

void lagrangeBasis(const ChebyshevGrid& grid, double s, Eigen::VectorXd& l) {
  const Eigen::VectorXd& x = grid.nodes();
  l.setZero(grid.size());
  const int j = grid.nearestNode(s);
  if (s == x[j]) {
    l[j] = 1.0;
    return;
  }
  for (int k = 0; k < grid.size(); ++k) l[k] = grid.barycentricWeights()[k] / (s - x[k]);
  l /= l.sum();
}

InterpolantMaximum maximumOn(const ChebyshevGrid& grid, const Eigen::VectorXd& values,
                             const Eigen::VectorXd& slope, double lo, double hi) {
  const IntervalEnds e{lo,
                       hi,
                       grid.interpolate(values, lo),
                       grid.interpolate(values, hi),
                       grid.interpolate(slope, lo),
                       grid.interpolate(slope, hi)};
  double sample_s[kSamples - 1], sample_value[kSamples - 1];
  for (int i = 0; i < kSamples - 1; ++i) {
    sample_s[i] = lo + (hi - lo) * (i + 1) / kSamples;
    sample_value[i] = grid.interpolate(values, sample_s[i]);
  }
  return bestOf(grid, values, slope, e, sample_s, sample_value);
}

IntervalMaxima::IntervalMaxima(const ChebyshevGrid& grid)
    : grid_(grid), samples_(sharedByDegree<Samples>(grid.degree(), samplesOf)) {}

IntervalMaxima::Samples IntervalMaxima::samplesOf(int degree) {
  const ChebyshevGrid grid(degree);
  const int per = kSamples - 1;
  Samples out;
  out.s.resize(grid.degree() * per);
  out.matrix.resize(out.s.size(), grid.size());
  for (int k = 0; k < grid.degree(); ++k)
    for (int i = 0; i < per; ++i) {
      const double lo = grid.nodes()[k + 1], hi = grid.nodes()[k];
      const int row = k * per + i;
      out.s[row] = lo + (hi - lo) * (i + 1) / kSamples;
      out.matrix.row(row) = lagrangeBasis(grid, out.s[row]).transpose();
    }
  return out;
}

std::vector<InterpolantMaximum> IntervalMaxima::operator()(const Eigen::VectorXd& values) const {
  const Eigen::VectorXd& x = grid_.nodes();
  const Eigen::VectorXd samples = samples_->matrix * values;
  const Eigen::VectorXd slope = grid_.differentiation() * values;  // nodal G'
  std::vector<InterpolantMaximum> out;
  out.reserve(grid_.degree());
  const int per = kSamples - 1;
  for (int k = 0; k < grid_.degree(); ++k) {
    const IntervalEnds e{x[k + 1], x[k], values[k + 1], values[k], slope[k + 1], slope[k]};
    out.push_back(bestOf(grid_, values, slope, e, &samples_->s[k * per], &samples[k * per]));
  }
  return out;
}

}  // namespace gaitopt
