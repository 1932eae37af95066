// Cubic smoothing spline: exact on straight lines, interpolating at λ = 0, gain 1/2 at the
// cutoff that smoothingLambdaForCutoff targets, and zero-phase smooth derivatives.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "gaitopt/math/smoothing_spline.hpp"

using namespace gaitopt;

namespace {

Eigen::VectorXd uniformTimes(int n, double dt) {
  return Eigen::VectorXd::LinSpaced(n, 0.0, (n - 1) * dt);
}

// Amplitude of the fitted spline to a unit sine of frequency f, in the middle of the record.
double midRecordGain(double f, double cutoff) {
  const double dt = 1.0 / 60.0;
  const Eigen::VectorXd t = uniformTimes(601, dt);
  const Eigen::VectorXd y = (2 * M_PI * f * t.array()).sin();
  const SmoothingSpline s(t, y, smoothingLambdaForCutoff(dt, cutoff));
  double amplitude = 0.0;
  for (int k = 200; k < 400; ++k) amplitude = std::max(amplitude, std::abs(s.evaluate(t(k))(0)));
  return amplitude;
}

}  // namespace

TEST_CASE("smoothing spline reproduces straight lines at any lambda", "[spline]") {
  const Eigen::VectorXd t = (Eigen::VectorXd(5) << 0.0, 0.1, 0.35, 0.4, 1.0).finished();
  Eigen::MatrixXd y(5, 2);
  y.col(0) = 2.0 - 3.0 * t.array();
  y.col(1) = 0.5 * t.array();
  const SmoothingSpline s(t, y, 10.0);
  for (double x : {0.0, 0.2, 0.77, 1.0, 1.3}) {
    CHECK(s.evaluate(x)(0) == Approx(2.0 - 3.0 * x).margin(1e-12));
    CHECK(s.evaluate(x, 1)(0) == Approx(-3.0).margin(1e-10));
    CHECK(s.evaluate(x, 2)(1) == Approx(0.0).margin(1e-9));
  }
}

TEST_CASE("smoothing spline interpolates at lambda 0 with natural ends", "[spline]") {
  const Eigen::VectorXd t = uniformTimes(7, 0.5);
  const Eigen::VectorXd y = (t.array() * 1.7).cos();
  const SmoothingSpline s(t, y, 0.0);
  for (int k = 0; k < 7; ++k) CHECK(s.evaluate(t(k))(0) == Approx(y(k)).margin(1e-12));
  CHECK(s.evaluate(t(0), 2)(0) == Approx(0.0).margin(1e-12));
  CHECK(s.evaluate(t(6), 2)(0) == Approx(0.0).margin(1e-12));
  // Continuity of value, slope and curvature at an inner knot.
  for (int order = 0; order < 3; ++order)
    CHECK(s.evaluate(t(3) - 1e-9, order)(0) == Approx(s.evaluate(t(3) + 1e-9, order)(0)).margin(1e-6));
}

TEST_CASE("smoothing spline cutoff: gain 1/2 at the cutoff, ~1 well below", "[spline]") {
  CHECK(midRecordGain(6.0, 6.0) == Approx(0.5).margin(0.03));
  CHECK(midRecordGain(1.0, 6.0) == Approx(1.0).margin(0.003));
  CHECK(midRecordGain(15.0, 6.0) < 0.05);
}

TEST_CASE("smoothing spline gives accurate derivatives of noisy slow signals", "[spline]") {
  const double dt = 1.0 / 60.0;
  const Eigen::VectorXd t = uniformTimes(151, dt);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1e-3);
  Eigen::VectorXd y = (2 * M_PI * t.array()).sin();
  for (Eigen::Index k = 0; k < y.size(); ++k) y(k) += noise(rng);
  const SmoothingSpline s(t, y, smoothingLambdaForCutoff(dt, 6.0));
  double worst_v = 0.0, worst_a = 0.0;
  for (double x = 0.5; x < 2.0; x += 1.0 / 600.0) {
    worst_v = std::max(worst_v, std::abs(s.evaluate(x, 1)(0) - 2 * M_PI * std::cos(2 * M_PI * x)));
    worst_a = std::max(worst_a, std::abs(s.evaluate(x, 2)(0) + 4 * M_PI * M_PI * std::sin(2 * M_PI * x)));
  }
  CHECK(worst_v < 0.02 * 2 * M_PI);
  CHECK(worst_a < 0.1 * 4 * M_PI * M_PI);
}
