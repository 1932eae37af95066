// The Forsythe-Malcolm-Moler cubic spline of OpenSim's SimmSpline: its end conditions take the
// third derivative of the cubic through the four end knots, so a cubic is reproduced exactly
// (and a parabola from three knots, a line from two); knots are interpolated; beyond the ends
// the spline continues along its end tangent.
#include <catch2/catch.hpp>

#include <vector>

#include "gaitopt/math/fmm_spline.hpp"

using gaitopt::fmmSplineValue;

TEST_CASE("fmm spline: cubics, parabolas and lines are reproduced", "[spline]") {
  const auto cubic = [](double x) { return 0.3 - 1.2 * x + 0.7 * x * x - 0.25 * x * x * x; };
  const std::vector<double> xs{-2.0, -1.3, -0.2, 0.4, 1.1, 2.5};
  std::vector<double> ys;
  for (const double x : xs) ys.push_back(cubic(x));
  for (double x = -2.0; x <= 2.5; x += 0.07) CHECK(fmmSplineValue(xs, ys, x) == Approx(cubic(x)).margin(1e-12));

  const auto parabola = [](double x) { return 1.0 + 0.5 * x - 2.0 * x * x; };
  const std::vector<double> x3{-1.0, 0.3, 2.0};
  const std::vector<double> y3{parabola(-1.0), parabola(0.3), parabola(2.0)};
  for (double x = -1.0; x <= 2.0; x += 0.1) CHECK(fmmSplineValue(x3, y3, x) == Approx(parabola(x)).margin(1e-12));

  CHECK(fmmSplineValue({0.0, 2.0}, {1.0, 5.0}, 0.5) == Approx(2.0));
  CHECK(fmmSplineValue({0.0, 2.0}, {1.0, 5.0}, -1.0) == Approx(-1.0));
}

TEST_CASE("fmm spline: knots interpolated, tangent extrapolation", "[spline]") {
  const std::vector<double> xs{-2.0944, -1.22173, -0.523599, -0.349066, -0.174533, 0.159149, 2.0944};
  const std::vector<double> ys{-0.4226, -0.4082, -0.399, -0.3976, -0.3966, -0.395264, -0.396};
  for (std::size_t i = 0; i < xs.size(); ++i) CHECK(fmmSplineValue(xs, ys, xs[i]) == Approx(ys[i]).margin(1e-15));
  // Beyond the ends: a straight line with the end slope (central differences just inside).
  const double h = 1e-6;
  const double slope_lo = (fmmSplineValue(xs, ys, xs.front() + 2 * h) - fmmSplineValue(xs, ys, xs.front())) / (2 * h);
  CHECK(fmmSplineValue(xs, ys, xs.front() - 0.5) == Approx(ys.front() - 0.5 * slope_lo).margin(1e-7));
  const double slope_hi = (fmmSplineValue(xs, ys, xs.back()) - fmmSplineValue(xs, ys, xs.back() - 2 * h)) / (2 * h);
  CHECK(fmmSplineValue(xs, ys, xs.back() + 0.5) == Approx(ys.back() + 0.5 * slope_hi).margin(1e-7));
  // C1 and C2 at an inner knot.
  const double k = xs[3];
  const auto d1 = [&](double x, double s) { return (fmmSplineValue(xs, ys, x + s) - fmmSplineValue(xs, ys, x)) / s; };
  CHECK(d1(k, 1e-7) == Approx(d1(k, -1e-7)).margin(1e-5));
}
