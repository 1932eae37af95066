#pragma once
// Least-distance QP on a handful of variables (the constrained control law (4.57), (4.60): the
// feasible input closest to the desired one):
//   min Σ w_i (x_i − x0_i)²  s.t.  G x ≤ h,
// by enumerating the active sets of at most n = dim x constraints in order of size and
// returning the first Karush–Kuhn–Tucker point (multipliers ≥ 0, every row feasible): the
// problem is strictly convex, so that point is the optimum. Exhaustive enumeration rather than
// a general solver because n ≤ 4 and m ≤ 14 here (≤ 1 471 sets of 4×4 solves, and only when x0
// is infeasible), it has no iteration, no cycling and no feasible start to find; Debian ships no
// small dense QP library (eiquadprog, qpOASES, ProxSuite are not packaged).
#include <Eigen/Core>

namespace gaitopt {

struct SmallQpResult {
  bool feasible = false;  // false: no x satisfies G x ≤ h (x is then x0)
  int active = 0;         // constraints active at the optimum
  Eigen::VectorXd x;
};

// `tolerance`: relative slack accepted on the rows and multipliers (scaled by ‖row‖·‖x‖ + |h|).
SmallQpResult solveLeastDistanceQp(const Eigen::MatrixXd& G, const Eigen::VectorXd& h,
                                   const Eigen::VectorXd& w, const Eigen::VectorXd& x0,
                                   double tolerance = 1e-10);

}  // namespace gaitopt
