#pragma once
// ∫|p| and ∫max(0, p) over [-1, 1] for the Chebyshev interpolant p of nodal values, split at
// p's sign changes. The Clenshaw–Curtis sum of |f_k| is only first-order accurate across a kink
// of |f|; integrating the (smooth) interpolant of f piece by piece between its roots is exact
// for the interpolant, hence as accurate as the plain quadrature of a smooth f. The values may
// be AD scalars: the roots are located on the plain values, and the integral's derivatives are
// those of the interpolant's pieces (the Leibniz terms of the moving roots vanish, p = 0 there).
#include <Eigen/Core>
#include <vector>

#include "gaitopt/math/chebyshev.hpp"

namespace gaitopt {

// A sign change of the interpolant: its position s in [-1, 1] and the slope p′(s) there.
struct InterpolantSignChange {
  double s;
  double slope;
};

// Sign changes of the interpolant of `values` in [-1, 1], in decreasing s (the nodes' order):
// one between consecutive nodes of opposite signs, and a pair around an extremum between nodes
// of equal sign next to a node where |f| has a discrete local minimum, where p′ changes sign,
// the smaller |value| is within the interval's width times the larger |p′| and the extremum
// crosses zero. Not seen: a pair between two nodes where p′ has equal signs, away from a dip
// of |f|, or where p bends by more than that (p would vary on a scale finer than the grid
// resolves). Sign convention: 0 counts as positive. Located by
// safeguarded Newton on the Chebyshev series (Clenshaw, O(n) per step) to rounding.
std::vector<InterpolantSignChange> interpolantSignChanges(const ChebyshevGrid& grid,
                                                          const Eigen::VectorXd& values);

// Weights u with u·f = ∫_{-1}^{1} |p(s)| ds for the interpolant p of f whose sign changes
// (interpolantSignChanges) are `roots`.
Eigen::VectorXd absIntegralWeights(const ChebyshevGrid& grid, const Eigen::VectorXd& values,
                                   const std::vector<InterpolantSignChange>& roots);

// A root of the interpolant, located on the plain values, with its derivatives with respect
// to the values by the implicit-function theorem (ds = −dp / p′): one Newton step on the
// scalar type (p ≈ 0 there, its derivatives carry the root's).
template <class Vec>
ValueTypeOf<Vec> interpolantRoot(const ChebyshevGrid& grid, const Vec& values,
                                 const InterpolantSignChange& root) {
  using T = ValueTypeOf<Vec>;
  if (root.slope == 0.0) return T(root.s);
  return T(T(root.s) - grid.interpolate(values, root.s) / root.slope);
}

// ∫_{-1}^{1} p(s) ds: the Clenshaw–Curtis sum w·f, for values of any scalar type.
template <class Vec>
ValueTypeOf<Vec> integrateReference(const ChebyshevGrid& grid, const Vec& values) {
  ValueTypeOf<Vec> total(0.0);
  for (int k = 0; k < grid.size(); ++k) total += grid.weights()[k] * values[k];
  return total;
}

// ∫_{-1}^{1} |p(s)| ds; the roots where p changes sign are appended to `roots` (decreasing s).
template <class Vec>
ValueTypeOf<Vec> integrateAbs(const ChebyshevGrid& grid, const Vec& values,
                              std::vector<ValueTypeOf<Vec>>& roots) {
  using T = ValueTypeOf<Vec>;
  Eigen::VectorXd plain(grid.size());
  for (int k = 0; k < grid.size(); ++k) plain[k] = valueOf(values[k]);
  const std::vector<InterpolantSignChange> found = interpolantSignChanges(grid, plain);
  const Eigen::VectorXd u = absIntegralWeights(grid, plain, found);
  T total(0.0);
  for (int k = 0; k < grid.size(); ++k) total += u[k] * values[k];
  for (const InterpolantSignChange& root : found)
    roots.push_back(interpolantRoot(grid, values, root));
  return total;
}

// ∫_{-1}^{1} max(0, p(s)) ds = (∫p + ∫|p|) / 2, roots appended as by integrateAbs.
template <class Vec>
ValueTypeOf<Vec> integratePositivePart(const ChebyshevGrid& grid, const Vec& values,
                                       std::vector<ValueTypeOf<Vec>>& roots) {
  return 0.5 * (integrateReference(grid, values) + integrateAbs(grid, values, roots));
}

}  // namespace gaitopt
