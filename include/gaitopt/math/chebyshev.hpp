#pragma once
// Chebyshev–Lobatto spectral grid on the reference coordinate s ∈ [-1, 1].
//
// The gait evaluator integrates the zero dynamics over an interval [a, b] whose end points
// depend on the optimisation parameters. Keeping the grid in a fixed coordinate s and mapping
// it affinely to [a, b] makes every node move smoothly with (a, b), so the same templated code
// run on an AD scalar yields exact forward-mode derivatives. All matrices are double-only and
// precomputed once (src/chebyshev.cpp); everything that touches parameter-dependent data is a
// template on the scalar.
//
// Conventions: s_k = cos(pi k / n), k = 0..n, so s_0 = +1 and s_n = -1 (decreasing).
// The interval map sends s = +1 to x = a and s = -1 to x = b; dx/ds = -(b - a)/2.
#include <cmath>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "gaitopt/math/scalar.hpp"

namespace gaitopt {

// Element type of a vector-like container (Eigen vector/expression or std::vector); lets the
// grid accept nodal values of any scalar type without the caller naming it.
template <class Vec>
using ValueTypeOf = std::decay_t<decltype(std::declval<const Vec&>()[0])>;

// Precomputed, double-only data for the n+1 Chebyshev–Lobatto points s_k = cos(pi k / n).
class ChebyshevGrid {
 public:
  // Builds nodes, quadrature weights, cumulative-integration, differentiation matrices; n >= 2.
  explicit ChebyshevGrid(int n);

  // Polynomial degree n (number of intervals), for callers that size things by n.
  int degree() const { return n_; }
  // Number of nodes n + 1, the length every nodal-value vector must have.
  int size() const { return n_ + 1; }

  // Nodes s_k in [-1, 1], s_0 = +1 ... s_n = -1; the fixed reference positions of the grid.
  const Eigen::VectorXd& nodes() const { return t_->nodes; }
  // Clenshaw–Curtis weights: ∫_{-1}^{1} f ds ≈ w·f, exact for polynomials of degree <= n.
  const Eigen::VectorXd& weights() const { return t_->weights; }
  // Cumulative integration anchored at s = +1: (Q f)_k ≈ ∫_{+1}^{s_k} f(s) ds (integrating
  // DOWN from +1, so negative for positive f); exact for polynomials of degree <= n.
  const Eigen::MatrixXd& cumulative() const { return t_->cumulative; }
  // Row r(s) with r(s)·f = ∫_{+1}^{s} p(t) dt for the interpolant p of f, at any s in [-1, 1]
  // (row k of cumulative() at node k); what an integral between two points that are not nodes,
  // e.g. the roots where a kinked integrand is split, needs.
  Eigen::RowVectorXd cumulativeAt(double s) const;
  // Σ_i factors[i]·cumulativeAt(points[i]) with a single matrix product: the weights of a sum of
  // integrals between many points (a piecewise integral) for the cost of one.
  Eigen::RowVectorXd cumulativeCombination(const std::vector<double>& points,
                                           const std::vector<double>& factors) const;
  // Values -> Chebyshev coefficients: p = Σ_j a_j T_j with a = C f, for the interpolant p of f
  // (evaluated by Clenshaw's recurrence in O(n), e.g. in a root search).
  const Eigen::MatrixXd& coefficients() const { return t_->coefficients; }
  // Spectral differentiation: (D f)_k = p'(s_k) for the interpolant p of f; lets callers get
  // nodal rates (e.g. velocities) of integrated quantities without finite differences.
  const Eigen::MatrixXd& differentiation() const { return t_->differentiation; }
  // Barycentric weights (-1)^k, halved at both ends; the stable way to evaluate the interpolant.
  const Eigen::VectorXd& barycentricWeights() const { return t_->barycentric; }

  // Index of the node nearest to s (by plain value); used to pick the numerically safe form.
  int nearestNode(double s) const;

  // Interpolant of the nodal values at s. Exactly returns values[k] when s equals node k (in
  // value), with correct derivatives w.r.t. s and the values for AD scalars. Works for s
  // slightly outside [-1, 1] too (polynomial extrapolation, e.g. for overshooting Newton steps).
  // The result type is the AD type if either the values or s are AD.
  template <class Scalar, class Vec>
  PromoteScalarT<ValueTypeOf<Vec>, Scalar> interpolate(const Vec& values, const Scalar& s) const {
    using R = PromoteScalarT<ValueTypeOf<Vec>, Scalar>;
    R p, dp;
    evaluate(values, s, false, p, dp);
    return p;
  }

  // d/ds of the interpolant at s (needed for Newton inversion in s); exact node handling as above.
  template <class Scalar, class Vec>
  PromoteScalarT<ValueTypeOf<Vec>, Scalar> interpolateDerivative(const Vec& values,
                                                                 const Scalar& s) const {
    using R = PromoteScalarT<ValueTypeOf<Vec>, Scalar>;
    R p, dp;
    evaluate(values, s, true, p, dp);
    return dp;
  }

  // Value and d/ds together in one O(n) pass; what a Newton step on the interpolant needs.
  template <class Scalar, class Vec>
  std::pair<PromoteScalarT<ValueTypeOf<Vec>, Scalar>, PromoteScalarT<ValueTypeOf<Vec>, Scalar>>
  interpolateWithDerivative(const Vec& values, const Scalar& s) const {
    using R = PromoteScalarT<ValueTypeOf<Vec>, Scalar>;
    R p, dp;
    evaluate(values, s, true, p, dp);
    return {p, dp};
  }

 private:
  // Barycentric evaluation rewritten around the nearest node j, with h = s - s_j:
  //   E = w_j + h Σ_{k≠j} w_k/(s-s_k)           (= h · barycentric denominator, never 0)
  //   q = Σ_{k≠j} w_k/(s-s_k) (f_k - f_j) / E    (= (p - f_j)/h, smooth through h = 0)
  //   p = f_j + h q
  //   p' = [w_j q + h Σ_{k≠j} w_k/(s-s_k) · (h q - (f_k - f_j))/(s-s_k)] / E
  // No division by s - s_j, so it is exact at nodes, free of the cancellation the plain
  // formula suffers next to a node, and a single smooth expression for AD.
  template <class Scalar, class Vec, class R>
  void evaluate(const Vec& values, const Scalar& s_in, bool want_derivative, R& p, R& dp) const {
    using V = ValueTypeOf<Vec>;
    using S = PromoteScalarT<Scalar, double>;  // int -> double, AD stays AD
    const S s = s_in;
    if (static_cast<int>(values.size()) != n_ + 1)
      throw std::invalid_argument("ChebyshevGrid: values must have size() = n + 1 entries");
    const int j = nearestNode(valueOf(s));
    const S h = s - t_->nodes[j];
    const V fj = values[j];
    S sum_c(0.0);
    R sum_cg(0.0);
    for (int k = 0; k <= n_; ++k) {
      if (k == j) continue;
      const S c = t_->barycentric[k] / (s - t_->nodes[k]);
      sum_c += c;
      const V g = values[k] - fj;
      sum_cg += c * g;
    }
    const S e = t_->barycentric[j] + h * sum_c;
    const R q = sum_cg / e;
    p = fj + h * q;
    if (!want_derivative) return;
    const R hq = h * q;
    R sum_d(0.0);
    for (int k = 0; k <= n_; ++k) {
      if (k == j) continue;
      const S d = s - t_->nodes[k];
      const S c = t_->barycentric[k] / d;
      const V g = values[k] - fj;
      const R diff = hq - g;
      sum_d += c * diff / d;
    }
    dp = (t_->barycentric[j] * q + h * sum_d) / e;
  }

  // The precomputed data, shared by every grid of the same degree (math/degree_cache.hpp keeps
  // the recently used degrees): building it costs O(n³), 77 ms at n = 320 (the feasibility
  // verdict's 10× finer check builds such grids at every call).
  struct Tables {
    Eigen::VectorXd nodes;
    Eigen::VectorXd weights;
    Eigen::MatrixXd cumulative;
    Eigen::MatrixXd antiderivative;  // nodal values -> Chebyshev coefficients of an antiderivative
    Eigen::MatrixXd coefficients;
    Eigen::MatrixXd differentiation;
    Eigen::VectorXd barycentric;
  };
  static std::shared_ptr<const Tables> sharedTables(int n);
  static Tables computeTables(int n);

  int n_;
  std::shared_ptr<const Tables> t_;
};

// ---------------------------------------------------------------------------------------------
// Affine map between s ∈ [-1, 1] and x ∈ [a, b], s = +1 <-> x = a, s = -1 <-> x = b.
// (a > b is allowed and is the alpha case: integrate from alpha_iSS down to alpha_fSS.)
// a and b may be double, int or AD independently; the result is AD if either is.

// Physical position of reference point s; how the grid nodes follow the parameters (a, b).
template <class A, class B>
PromoteScalarT<A, B> chebyshevToInterval(double s, const A& a, const B& b) {
  using R = PromoteScalarT<A, B>;
  const R ra = a;
  const R rb = b;
  return ra + (0.5 * (1.0 - s)) * (rb - ra);
}

// Reference coordinate of a physical point x (AD in any argument); used to evaluate the
// interpolant at a physical position, e.g. the initial guess for a Newton inversion.
template <class X, class A, class B>
PromoteScalarT<PromoteScalarT<X, A>, B> intervalToChebyshev(const X& x, const A& a, const B& b) {
  using R = PromoteScalarT<PromoteScalarT<X, A>, B>;
  const R rx = x;
  const R ra = a;
  const R rb = b;
  return 1.0 - 2.0 * (rx - ra) / (rb - ra);
}

// dx/ds = -(b - a)/2: the chain-rule factor between s-integrals/derivatives and x ones.
template <class A, class B>
PromoteScalarT<A, B> intervalJacobian(const A& a, const B& b) {
  using R = PromoteScalarT<A, B>;
  const R ra = a;
  const R rb = b;
  return -0.5 * (rb - ra);
}

// All node positions x_k mapped to [a, b]; where the integrand has to be sampled.
template <class A, class B>
Eigen::Matrix<PromoteScalarT<A, B>, Eigen::Dynamic, 1> mappedNodes(const ChebyshevGrid& grid,
                                                                   const A& a, const B& b) {
  Eigen::Matrix<PromoteScalarT<A, B>, Eigen::Dynamic, 1> x(grid.size());
  for (int k = 0; k < grid.size(); ++k) x[k] = chebyshevToInterval(grid.nodes()[k], a, b);
  return x;
}

// ∫_a^b f(x) dx from values f(x_k) at mappedNodes(grid, a, b); = (b - a)/2 · w·f. Signed, so
// for a > b it is minus the integral over [b, a], as the integration direction requires.
template <class Vec, class A, class B>
PromoteScalarT<ValueTypeOf<Vec>, PromoteScalarT<A, B>> integrateOverInterval(
    const ChebyshevGrid& grid, const Vec& values, const A& a, const B& b) {
  using V = ValueTypeOf<Vec>;
  using R = PromoteScalarT<V, PromoteScalarT<A, B>>;
  if (static_cast<int>(values.size()) != grid.size())
    throw std::invalid_argument("integrateOverInterval: values must have grid.size() entries");
  V acc(0.0);
  for (int k = 0; k < grid.size(); ++k) acc += grid.weights()[k] * values[k];
  const R jac = -intervalJacobian(a, b);
  return jac * acc;
}

// Running integrals F_k = ∫_a^{x_k} f(x) dx at every node (F_0 = 0, F_n = the total); =
// (dx/ds) · (Q f)_k. This is how time along the gait is accumulated from 1/α̇.
template <class Vec, class A, class B>
Eigen::Matrix<PromoteScalarT<ValueTypeOf<Vec>, PromoteScalarT<A, B>>, Eigen::Dynamic, 1>
cumulativeOverInterval(const ChebyshevGrid& grid, const Vec& values, const A& a, const B& b) {
  using V = ValueTypeOf<Vec>;
  using R = PromoteScalarT<V, PromoteScalarT<A, B>>;
  if (static_cast<int>(values.size()) != grid.size())
    throw std::invalid_argument("cumulativeOverInterval: values must have grid.size() entries");
  const R jac = intervalJacobian(a, b);
  const Eigen::MatrixXd& q = grid.cumulative();
  Eigen::Matrix<R, Eigen::Dynamic, 1> out(grid.size());
  for (int i = 0; i < grid.size(); ++i) {
    V acc(0.0);
    for (int k = 0; k < grid.size(); ++k) acc += q(i, k) * values[k];
    out[i] = jac * acc;
  }
  return out;
}

}  // namespace gaitopt
