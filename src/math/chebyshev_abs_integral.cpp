// Root location and integration weights of math/chebyshev_abs_integral.hpp (double only).
#include "gaitopt/math/chebyshev_abs_integral.hpp"

#include <algorithm>
#include <cmath>

#include "gaitopt/math/bracketed_root.hpp"

namespace gaitopt {

std::vector<double> interpolantSignChanges(const ChebyshevGrid& grid,
                                           const Eigen::VectorXd& values) {
  const Eigen::VectorXd slope = grid.differentiation() * values;
  const Eigen::VectorXd& s = grid.nodes();
  const auto p = [&grid, &values](double x) { return grid.interpolate(values, x); };
  const auto dp = [&grid, &values](double x) { return grid.interpolateDerivative(values, x); };
  std::vector<double> roots;
  for (int k = 0; k + 1 < grid.size(); ++k) {
    // Node k is the upper end of the interval: the brackets run from s_{k+1} up to s_k.
    const double lo = s[k + 1], hi = s[k], f_lo = values[k + 1], f_hi = values[k];
    if ((f_lo < 0.0) != (f_hi < 0.0)) {
      roots.push_back(bracketedRoot(p, lo, f_lo, hi, f_hi));
      continue;
    }
    // An extremum between the nodes can only cross zero if the values are within reach of the
    // slopes over the interval; the test skips the search for most extrema (and their cost).
    if ((slope[k + 1] < 0.0) == (slope[k] < 0.0) ||
        std::min(std::abs(f_lo), std::abs(f_hi)) >
            (hi - lo) * std::max(std::abs(slope[k]), std::abs(slope[k + 1])))
      continue;
    const double e = bracketedRoot(dp, lo, slope[k + 1], hi, slope[k]);
    const double f_e = p(e);
    if ((f_e < 0.0) == (f_lo < 0.0)) continue;
    roots.push_back(bracketedRoot(p, e, f_e, hi, f_hi));
    roots.push_back(bracketedRoot(p, lo, f_lo, e, f_e));
  }
  return roots;
}

Eigen::VectorXd absIntegralWeights(const ChebyshevGrid& grid, const Eigen::VectorXd& values,
                                   const std::vector<double>& roots) {
  // With F(s) = ∫_{+1}^{s} p = cumulativeAt(s)·f, each piece [e_{k+1}, e_k] between consecutive
  // ends (+1, the roots, −1) contributes σ_k (F(e_k) − F(e_{k+1})), σ_k its sign: that of p(+1)
  // in the first piece, alternating since every root is a sign change.
  std::vector<double> ends{1.0};
  ends.insert(ends.end(), roots.begin(), roots.end());
  ends.push_back(-1.0);
  Eigen::RowVectorXd upper = Eigen::RowVectorXd::Zero(grid.size());  // F at s = +1
  Eigen::VectorXd u = Eigen::VectorXd::Zero(grid.size());
  double sign = values[0] < 0.0 ? -1.0 : 1.0;
  for (std::size_t k = 0; k + 1 < ends.size(); ++k) {
    const Eigen::RowVectorXd lower =
        k + 2 == ends.size() ? Eigen::RowVectorXd(-grid.weights().transpose())
                             : grid.cumulativeAt(ends[k + 1]);
    u += sign * (upper - lower).transpose();
    upper = lower;
    sign = -sign;
  }
  return u;
}

}  // namespace gaitopt
