#pragma once
// The torque-envelope rows (3.46) between the nodes when the joints have Coulomb friction
// (1.21). Γ*_j holds Γs_j tanh(ω_j/ε), which turns over |ω_j| ≲ ε (ε = friction_smoothing,
// 0.05 rad/s) far faster than the grids resolve: the interpolant of a row's node values misses
// the turn between two nodes and rings around it over the whole phase (measured at 0.95 m/s:
// hip 2's row −24.2 and −2.6 N·m at two SS nodes, +4.1 N·m between them).
//
// Each row g = σΓ*_j − Γmax(ω_j) (σ = +1 the upper row, −1 the lower) is split into its smooth
// part h = g − σΓs tanh(ω/ε) and the friction term; h and w = σω are interpolated from the
// nodes, and the row between them is
//     g ≈ h + Γs tanh(w/ε),
// exact at the nodes, and between them up to the interpolation error of h and ω, which are
// smooth (the interpolant of g itself is off by up to 2Γs). An SS row is its largest value at
// the points of the verdict's 10× finer check inside the interval (opt/gait_problem.cpp), so
// that the row and the verdict see the same turn; a DS row, piecewise already
// (gait/ds_interval_maxima.hpp), its maximum on each piece's part of the interval (SplitRow).
#include <cmath>

#include <Eigen/Core>

#include "gaitopt/gait/constraints.hpp"
#include "gaitopt/math/chebyshev.hpp"
#include "gaitopt/math/chebyshev_maxima.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

struct CoulombSplit {
  double coulomb = 0.0;  // Γs_j [N·m]; 0: nothing to split
  double width = 1.0;    // ε [rad/s]
  double sigma = 1.0;    // +1: Γ*_j − Γmax, −1: −Γ*_j − Γmax
  int joint = 0;

  // The friction term's share of a row at speed ω (its derivative in ω: σ rowSlope(ω)).
  double term(double omega) const { return sigma * coulomb * std::tanh(omega / width); }
  // The row from h and w = σω at a point between the nodes.
  double row(double smooth, double w) const { return smooth + coulomb * std::tanh(w / width); }
  // Its first and second derivatives in w.
  double rowSlope(double w) const {
    const double t = std::tanh(w / width);
    return coulomb * (1.0 - t * t) / width;
  }
  double rowCurvature(double w) const {
    const double t = std::tanh(w / width);
    return -2.0 * coulomb * (1.0 - t * t) * t / (width * width);
  }
};

// The split of entry `sub` = 2j + i (joint j, i = 0 upper) of `group`'s rows at one point: only
// the torque envelope has one, and only for a joint with Coulomb friction.
inline CoulombSplit coulombSplit(const Model& m, int group, int sub) {
  CoulombSplit c;
  if (group != kTorqueSS && group != kTorqueDS) return c;
  c.joint = sub / 2;
  c.coulomb = m.coulomb(c.joint);
  c.width = m.options.friction_smoothing;
  c.sigma = sub % 2 == 0 ? 1.0 : -1.0;
  return c;
}

// One split row between the nodes of a grid: h + Γs tanh(w/ε), h and w the interpolants of
// their node values.
class SplitRow {
 public:
  SplitRow(const ChebyshevGrid& grid, const CoulombSplit& c, const Eigen::VectorXd& h,
           const Eigen::VectorXd& w);
  double value(double s);
  // The maximum over [lo, hi]: the best of evenly spaced samples, refined by Newton on the
  // row's derivative, so that at an interior maximum the envelope theorem gives the gradient.
  InterpolantMaximum maximumOn(double lo, double hi);

 private:
  struct At {
    double value, slope, curvature;
  };
  At at(double s);
  // Newton from `start` within [a, b]: the better of the two.
  InterpolantMaximum refine(const InterpolantMaximum& start, double a, double b);

  const ChebyshevGrid& grid_;
  const CoulombSplit& c_;
  Eigen::VectorXd h_, w_, h1_, h2_, w1_, w2_;  // values and derivatives at the nodes
  Eigen::VectorXd l_;                           // the Lagrange basis at the point at hand
};

}  // namespace gaitopt
