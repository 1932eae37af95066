// Interval maxima of a Chebyshev interpolant (math/chebyshev_maxima.hpp): the maximum against
// a dense scan of the interpolant, and the envelope-theorem gradient against central finite
// differences of the maximum itself.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

#include "gaitopt/math/chebyshev_maxima.hpp"

namespace {

using gaitopt::ChebyshevGrid;

// Nodal values of f(s; p) = p0 sin(3 s + p1) + p2 s², smooth in s and p.
Eigen::VectorXd sampled(const ChebyshevGrid& grid, const Eigen::Vector3d& p) {
  Eigen::VectorXd v(grid.size());
  for (int k = 0; k < grid.size(); ++k) {
    const double s = grid.nodes()[k];
    v[k] = p[0] * std::sin(3.0 * s + p[1]) + p[2] * s * s;
  }
  return v;
}

Eigen::MatrixXd sampledJacobian(const ChebyshevGrid& grid, const Eigen::Vector3d& p) {
  Eigen::MatrixXd j(grid.size(), 3);
  for (int k = 0; k < grid.size(); ++k) {
    const double s = grid.nodes()[k];
    j.row(k) << std::sin(3.0 * s + p[1]), p[0] * std::cos(3.0 * s + p[1]), s * s;
  }
  return j;
}

}  // namespace

TEST_CASE("interval maxima equal a dense scan of the interpolant", "[gait][chebyshev_maxima]") {
  const ChebyshevGrid grid(8);
  const gaitopt::IntervalMaxima maxima(grid);
  const Eigen::VectorXd v = sampled(grid, Eigen::Vector3d(1.0, 0.3, -0.4));
  const auto m = maxima(v);
  REQUIRE(static_cast<int>(m.size()) == grid.degree());
  int interior = 0;
  for (int k = 0; k < grid.degree(); ++k) {
    const double lo = grid.nodes()[k + 1], hi = grid.nodes()[k];
    double scan = -INFINITY;
    for (int i = 0; i <= 20000; ++i) scan = std::max(scan, grid.interpolate(v, lo + (hi - lo) * i / 20000.0));
    INFO("interval " << k);
    CHECK(m[k].s >= lo);
    CHECK(m[k].s <= hi);
    CHECK(m[k].value == Approx(grid.interpolate(v, m[k].s)).margin(1e-14));
    CHECK(m[k].value >= scan - 1e-12);
    CHECK(m[k].value <= scan + 1e-9);
    if (m[k].s > lo && m[k].s < hi) ++interior;
  }
  CHECK(interior >= 1);  // sin(3s) peaks inside an interval: the Newton branch is exercised
}

TEST_CASE("interval maximum gradient is the Lagrange-weighted node gradient",
          "[gait][chebyshev_maxima]") {
  const ChebyshevGrid grid(10);
  const gaitopt::IntervalMaxima maxima(grid);
  const Eigen::Vector3d p(0.8, -0.2, 0.5);
  const auto m = maxima(sampled(grid, p));
  const Eigen::MatrixXd jac = sampledJacobian(grid, p);
  const double h = 1e-6;
  int checked = 0;
  for (int k = 0; k < grid.degree(); ++k) {
    const Eigen::VectorXd grad = jac.transpose() * gaitopt::lagrangeBasis(grid, m[k].s);
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d up = p, down = p;
      up[i] += h;
      down[i] -= h;
      const double fd = (maxima(sampled(grid, up))[k].value - maxima(sampled(grid, down))[k].value) / (2.0 * h);
      INFO("interval " << k << ", parameter " << i);
      CHECK(grad[i] == Approx(fd).margin(1e-7));
      ++checked;
    }
  }
  CHECK(checked == 30);
}

TEST_CASE("lagrange basis reproduces the interpolant and is exact at nodes",
          "[gait][chebyshev_maxima]") {
  const ChebyshevGrid grid(7);
  const Eigen::VectorXd v = sampled(grid, Eigen::Vector3d(1.2, 0.1, 0.3));
  for (const double s : {-0.93, -0.2, 0.0, 0.41, 0.999})
    CHECK(gaitopt::lagrangeBasis(grid, s).dot(v) == Approx(grid.interpolate(v, s)).margin(1e-13));
  const Eigen::VectorXd at_node = gaitopt::lagrangeBasis(grid, grid.nodes()[3]);
  CHECK(at_node[3] == 1.0);
  CHECK(at_node.sum() == 1.0);
}

TEST_CASE("maximum on a sub-interval equals a dense scan of the interpolant",
          "[gait][chebyshev_maxima]") {
  const ChebyshevGrid grid(12);
  const Eigen::VectorXd v = sampled(grid, Eigen::Vector3d(1.0, 0.3, -0.4));
  const Eigen::VectorXd slope = grid.differentiation() * v;
  int interior = 0, at_end = 0;
  // Sub-intervals that do not start or end at nodes, as a switch time cuts a piece.
  const std::pair<double, double> cases[] = {{-0.93, -0.71}, {-0.7, -0.2}, {-0.35, 0.05},
                                             {0.1, 0.123},   {0.2, 0.97},  {-1.0, 1.0}};
  for (const auto& [lo, hi] : cases) {
    const gaitopt::InterpolantMaximum m = gaitopt::maximumOn(grid, v, slope, lo, hi);
    double scan = -INFINITY;
    for (int i = 0; i <= 20000; ++i) scan = std::max(scan, grid.interpolate(v, lo + (hi - lo) * i / 20000.0));
    INFO("[" << lo << ", " << hi << "]: max " << m.value << " at " << m.s << ", scan " << scan);
    CHECK(m.s >= lo);
    CHECK(m.s <= hi);
    CHECK(m.value == Approx(grid.interpolate(v, m.s)).margin(1e-14));
    CHECK(m.value >= scan - 1e-12);
    CHECK(m.value <= scan + 1e-7);  // the scan's step is up to 1e-4 here
    ++(m.s > lo && m.s < hi ? interior : at_end);
  }
  CHECK(interior >= 2);
  CHECK(at_end >= 2);
}

TEST_CASE("the interpolant's minimum equals a dense scan, its AD gradient finite differences",
          "[gait][chebyshev_maxima]") {
  using AD = Eigen::AutoDiffScalar<Eigen::Vector3d>;
  const ChebyshevGrid grid(9);
  // p0 sin(3s + p1) + p2 s² dips between two nodes for these parameters.
  const Eigen::Vector3d p(0.9, 0.4, 0.3);
  const Eigen::VectorXd v = sampled(grid, p);
  const double low = gaitopt::interpolantMinimum(grid, v);
  double scan = INFINITY;
  for (int i = 0; i <= 40000; ++i) scan = std::min(scan, grid.interpolate(v, -1.0 + i / 20000.0));
  INFO("minimum " << low << ", scan " << scan << ", lowest node " << v.minCoeff());
  CHECK(low <= scan + 1e-12);
  CHECK(low >= scan - 1e-9);
  CHECK(low < v.minCoeff() - 1e-3);  // the minimum lies between the nodes
  // AD values: d/dp of the minimum, the minimiser held fixed (envelope theorem).
  const Eigen::MatrixXd jac = sampledJacobian(grid, p);
  Eigen::Matrix<AD, Eigen::Dynamic, 1> v_ad(grid.size());
  for (int k = 0; k < grid.size(); ++k) v_ad[k] = AD(v[k], jac.row(k).transpose());
  const AD low_ad = gaitopt::interpolantMinimum(grid, v_ad);
  CHECK(low_ad.value() == low);
  const double h = 1e-6;
  for (int i = 0; i < 3; ++i) {
    Eigen::Vector3d up = p, down = p;
    up[i] += h;
    down[i] -= h;
    const double fd = (gaitopt::interpolantMinimum(grid, sampled(grid, up)) -
                       gaitopt::interpolantMinimum(grid, sampled(grid, down))) / (2.0 * h);
    INFO("parameter " << i);
    CHECK(low_ad.derivatives()[i] == Approx(fd).margin(1e-7));
  }
}
