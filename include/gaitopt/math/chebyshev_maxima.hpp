#pragma once
// Maxima of a Chebyshev interpolant between its nodes. A semi-infinite constraint sampled at
// the Chebyshev–Lobatto nodes of its phase has the interpolant G(s) = Σ_k l_k(s) g_k; its
// maximum over [s_{k+1}, s_k] is the constraint's value between those two nodes, and by the
// envelope theorem its gradient is Σ_k l_k(s*) ∇g_k (at a node, the node's own row). The
// minimum over the whole grid follows from the maxima of −g.
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "gaitopt/math/chebyshev.hpp"

namespace gaitopt {

struct InterpolantMaximum {
  double s = 0.0;      // where, in the grid's coordinate
  double value = 0.0;  // G(s)
};

// Lagrange basis at s: G(s) = l(s)·values for any nodal values (a unit vector at a node).
Eigen::VectorXd lagrangeBasis(const ChebyshevGrid& grid, double s);
// The same into `l` (resized), for callers that reuse one vector over many points.
void lagrangeBasis(const ChebyshevGrid& grid, double s, Eigen::VectorXd& l);

// Maximum of the interpolant of `values` over any [lo, hi] ⊂ [−1, 1] (slope: its nodal
// derivative, grid.differentiation() · values), found as IntervalMaxima finds it between two
// nodes; what a sub-interval cut by a switch time needs.
InterpolantMaximum maximumOn(const ChebyshevGrid& grid, const Eigen::VectorXd& values,
                             const Eigen::VectorXd& slope, double lo, double hi);

class IntervalMaxima {
 public:
  explicit IntervalMaxima(const ChebyshevGrid& grid);
  // For each interval k = 0..n−1 between nodes s_{k+1} < s_k, the maximum of the interpolant
  // of `values` over the closed interval: a sample of each interval (one matrix product), then
  // Newton on G' = 0 where a sample beats both nodes or G rises from the higher node inwards.
  std::vector<InterpolantMaximum> operator()(const Eigen::VectorXd& values) const;

 private:
  // Of the grid's degree, shared (math/degree_cache.hpp): an evaluation's saturation cap
  // (interpolantMinimum) builds an IntervalMaxima each time.
  struct Samples {
    Eigen::VectorXd s;       // interior sample points, kSamples − 1 per interval
    Eigen::MatrixXd matrix;  // interpolation matrix onto them
  };
  static Samples samplesOf(int degree);

  const ChebyshevGrid& grid_;
  std::shared_ptr<const Samples> samples_;
};

// Minimum of the interpolant of `values` over [−1, 1] (nodes included): the lowest of the
// interval maxima of −values. The values may be AD scalars: the minimiser s* is located on the
// plain values and held fixed, so the derivatives are l(s*)·∇values (the envelope theorem).
template <class Vec>
ValueTypeOf<Vec> interpolantMinimum(const ChebyshevGrid& grid, const Vec& values) {
  Eigen::VectorXd negated(grid.size());
  for (int k = 0; k < grid.size(); ++k) negated[k] = -valueOf(values[k]);
  InterpolantMaximum lowest{0.0, -std::numeric_limits<double>::infinity()};
  for (const InterpolantMaximum& m : IntervalMaxima(grid)(negated))
    if (m.value > lowest.value) lowest = m;
  return grid.interpolate(values, lowest.s);
}

}  // namespace gaitopt
