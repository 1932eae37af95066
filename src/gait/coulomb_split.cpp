#include "gaitopt/gait/coulomb_split.hpp"

#include <algorithm>
#include <cmath>

namespace gaitopt {
namespace {

// Samples per unit of the grid's coordinate: the turn spans ~ε/|ω̇| in time, a tenth of a DS
// piece or more on the shipped gaits; Newton then finds the maximum between two samples.
constexpr int kSamplesPerUnit = 32;
constexpr int kNewtonSteps = 20;

// The row and its first two derivatives in s at one point.
struct RowAt {
  double value, slope, curvature;
};

struct SplitInterpolants {
  const ChebyshevGrid& grid;
  const CoulombSplit& c;
  const Eigen::VectorXd &h, &w;
  Eigen::VectorXd h1, h2, w1, w2;  // derivatives at the nodes
  Eigen::VectorXd l;               // the Lagrange basis at the point at hand

  SplitInterpolants(const ChebyshevGrid& g, const CoulombSplit& split, const Eigen::VectorXd& hv,
                    const Eigen::VectorXd& wv)
      : grid(g), c(split), h(hv), w(wv) {
    const Eigen::MatrixXd& d = grid.differentiation();
    h1 = d * h;
    h2 = d * h1;
    w1 = d * w;
    w2 = d * w1;
  }
  double value(double s) {
    lagrangeBasis(grid, s, l);
    return c.row(l.dot(h), l.dot(w));
  }
  RowAt at(double s) {
    lagrangeBasis(grid, s, l);
    const double wv = l.dot(w), ws = l.dot(w1);
    return {c.row(l.dot(h), wv), l.dot(h1) + c.rowSlope(wv) * ws,
            l.dot(h2) + c.rowSlope(wv) * l.dot(w2) + c.rowCurvature(wv) * ws * ws};
  }
};

}  // namespace

InterpolantMaximum splitMaximumOn(const ChebyshevGrid& grid, const CoulombSplit& c,
                                  const Eigen::VectorXd& h, const Eigen::VectorXd& w, double lo,
                                  double hi) {
  SplitInterpolants f(grid, c, h, w);
  const int n = std::max(2, static_cast<int>(std::ceil(kSamplesPerUnit * (hi - lo))));
  const double step = (hi - lo) / n;
  InterpolantMaximum best{lo, f.value(lo)};
  for (int i = 1; i <= n; ++i) {
    const double s = i == n ? hi : lo + i * step;
    const double v = f.value(s);
    if (v > best.value) best = {s, v};
  }
  // Newton on the derivative within the samples around the best one, kept if it climbs.
  const double a = std::max(lo, best.s - step), b = std::min(hi, best.s + step);
  double s = best.s;
  for (int it = 0; it < kNewtonSteps; ++it) {
    const RowAt r = f.at(s);
    if (!(r.curvature < 0.0)) break;
    const double next = std::clamp(s - r.slope / r.curvature, a, b);
    if (std::abs(next - s) <= 1e-14) break;
    s = next;
  }
  const double v = f.value(s);
  if (v > best.value) best = {s, v};
  return best;
}

}  // namespace gaitopt
