#include "gaitopt/gait/coulomb_split.hpp"

#include <algorithm>
#include <cmath>

namespace gaitopt {
namespace {

// Samples per unit of the grid's coordinate, at least kMinSamples on an interval: the turn
// spans ~ε/|ω̇| in time, a tenth of a DS piece or more on the shipped gaits; Newton then finds
// the maximum between two samples.
constexpr int kSamplesPerUnit = 32;
constexpr int kMinSamples = 10;
constexpr int kNewtonSteps = 20;

}  // namespace

SplitRow::SplitRow(const ChebyshevGrid& grid, const CoulombSplit& c, const Eigen::VectorXd& h,
                   const Eigen::VectorXd& w)
    : grid_(grid), c_(c), h_(h), w_(w) {
  const Eigen::MatrixXd& d = grid.differentiation();
  h1_ = d * h_;
  h2_ = d * h1_;
  w1_ = d * w_;
  w2_ = d * w1_;
}

double SplitRow::value(double s) {
  lagrangeBasis(grid_, s, l_);
  return c_.row(l_.dot(h_), l_.dot(w_));
}

SplitRow::At SplitRow::at(double s) {
  lagrangeBasis(grid_, s, l_);
  const double w = l_.dot(w_), ws = l_.dot(w1_);
  return {c_.row(l_.dot(h_), w), l_.dot(h1_) + c_.rowSlope(w) * ws,
          l_.dot(h2_) + c_.rowSlope(w) * l_.dot(w2_) + c_.rowCurvature(w) * ws * ws};
}

InterpolantMaximum SplitRow::refine(const InterpolantMaximum& start, double a, double b) {
  double s = start.s;
  for (int it = 0; it < kNewtonSteps; ++it) {
    const At r = at(s);
    if (!(r.curvature < 0.0)) break;
    const double next = std::clamp(s - r.slope / r.curvature, a, b);
    if (std::abs(next - s) <= 1e-14) break;
    s = next;
  }
  const double v = value(s);
  return v > start.value ? InterpolantMaximum{s, v} : start;
}

InterpolantMaximum SplitRow::maximumOn(double lo, double hi) {
  const int n = std::max(kMinSamples, static_cast<int>(std::ceil(kSamplesPerUnit * (hi - lo))));
  const double step = (hi - lo) / n;
  InterpolantMaximum best{lo, value(lo)};
  for (int i = 1; i <= n; ++i) {
    const double s = i == n ? hi : lo + i * step;
    const double v = value(s);
    if (v > best.value) best = {s, v};
  }
  return refine(best, std::max(lo, best.s - step), std::min(hi, best.s + step));
}

}  // namespace gaitopt
