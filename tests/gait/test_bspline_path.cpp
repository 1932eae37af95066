// The B-spline basis of the virtual constraints (parameterisation basis: bspline): the curve
// interpolates its data with C² continuity, reproduces cubics (so it equals the polynomial
// basis on a gait whose path is a cubic), and its exact gradients, through the same evaluator,
// equal finite differences.
#include <catch2/catch.hpp>
#include <cmath>
#include <type_traits>

#include "gaitopt/gait/leg_geometry.hpp"
#include "gaitopt/gait/path_curve.hpp"
#include "gaitopt/gait/richer_parameterisation.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/yaml_reader.hpp"
#include "test_gait_support.hpp"
#include "test_gradient_check.hpp"

using namespace gaitopt;

namespace {

// Decreasing abscissae, as α in single support.
struct SplineData {
  double x0 = 0.3, x1 = -0.4, y0 = -2.7, y1 = -2.2, m0 = 0.8, m1 = -1.3;
  std::vector<double> xs, ys;
  explicit SplineData(int K) {
    for (int k = 1; k <= K; ++k) {
      xs.push_back(x0 + (x1 - x0) * k / (K + 1.0));
      ys.push_back(-2.5 + 0.1 * std::sin(3.0 * k));
    }
  }
  PathCurve<double> curve(PathBasis basis) const {
    return pathThrough(basis, x0, y0, m0, xs, ys, x1, y1, m1);
  }
};

GaitOptions withBasis(int ss, int ds, PathBasis basis) {
  GaitOptions o = test::viscousOptions();
  o.parameterisation.ss_points = ss;
  o.parameterisation.ds_points = ds;
  o.parameterisation.basis = basis;
  return o;
}

}  // namespace

TEST_CASE("B-spline path: interpolation, clamped ends, C2 at the knots", "[gait][bspline]") {
  for (int K = 0; K <= 5; ++K) {
    const SplineData d(K);
    const PathCurve<double> c = d.curve(PathBasis::BSpline);
    INFO("K = " << K);
    REQUIRE(c.pieces.size() == static_cast<std::size_t>(K + 1));
    CHECK(c(d.x0).value == Approx(d.y0).margin(1e-14));
    CHECK(c(d.x1).value == Approx(d.y1).margin(1e-13));
    CHECK(c(d.x0).first == Approx(d.m0).margin(1e-12));
    CHECK(c(d.x1).first == Approx(d.m1).margin(1e-12));
    for (int k = 0; k < K; ++k) {
      CHECK(c(d.xs[k]).value == Approx(d.ys[k]).margin(1e-13));
      // Both pieces meeting at the knot agree in value, slope and curvature.
      const PolyValue<double> left = c.pieces[k](d.xs[k]), right = c.pieces[k + 1](d.xs[k]);
      CHECK(left.value == Approx(right.value).margin(1e-12));
      CHECK(left.first == Approx(right.first).margin(1e-10));
      CHECK(left.second == Approx(right.second).margin(1e-8));
    }
  }
}

TEST_CASE("B-spline path equals the polynomial basis on a cubic", "[gait][bspline]") {
  SplineData d(3);
  const auto cubic = [](double x) { return -2.5 + 0.4 * x - 1.1 * x * x + 2.3 * x * x * x; };
  const auto slope = [](double x) { return 0.4 - 2.2 * x + 6.9 * x * x; };
  d.y0 = cubic(d.x0);
  d.y1 = cubic(d.x1);
  d.m0 = slope(d.x0);
  d.m1 = slope(d.x1);
  for (std::size_t k = 0; k < d.xs.size(); ++k) d.ys[k] = cubic(d.xs[k]);
  const PathCurve<double> s = d.curve(PathBasis::BSpline), p = d.curve(PathBasis::Polynomial);
  REQUIRE(p.pieces.size() == 1);
  for (int i = 0; i <= 40; ++i) {
    const double x = d.x0 + (d.x1 - d.x0) * i / 40.0;
    CHECK(s(x).value == Approx(cubic(x)).margin(1e-12));
    CHECK(s(x).first == Approx(p(x).first).margin(1e-10));
    CHECK(s(x).second == Approx(p(x).second).margin(1e-8));
  }
  // A non-cubic data set is where they differ.
  const SplineData e(3);
  CHECK(std::abs(e.curve(PathBasis::BSpline)(-0.1).value -
                 e.curve(PathBasis::Polynomial)(-0.1).value) > 1e-4);
}

TEST_CASE("B-spline path derivatives equal finite differences", "[gait][bspline]") {
  using AD = Eigen::AutoDiffScalar<Eigen::VectorXd>;
  const SplineData d(3);
  // Differentiated data: y0, m1 and the interior values; evaluated at x.
  const int n = 2 + static_cast<int>(d.ys.size());
  Eigen::VectorXd theta(n);
  theta << d.y0, d.m1, d.ys[0], d.ys[1], d.ys[2];
  const auto at = [&](const auto& th, const auto& x) {
    using S = std::decay_t<decltype(x)>;
    const S c0 = S(0.0) * th(0);  // a constant carrying the derivative's size
    std::vector<S> xs, ys;
    for (std::size_t k = 0; k < d.xs.size(); ++k) {
      xs.push_back(c0 + d.xs[k]);
      ys.push_back(th(2 + static_cast<int>(k)));
    }
    return pathThrough(PathBasis::BSpline, S(c0 + d.x0), S(th(0)), S(c0 + d.m0), xs, ys,
                       S(c0 + d.x1), S(c0 + d.y1), S(th(1)))(x);
  };
  Eigen::Matrix<AD, Eigen::Dynamic, 1> th_ad(n);
  for (int i = 0; i < n; ++i) th_ad(i) = AD(theta(i), n, i);
  for (double x : {0.25, 0.0, -0.13, -0.38}) {
    const PolyValue<AD> v = at(th_ad, AD(x, Eigen::VectorXd::Zero(n)));
    for (int i = 0; i < n; ++i) {
      const double h = 1e-6;
      Eigen::VectorXd tp = theta, tm = theta;
      tp(i) += h;
      tm(i) -= h;
      const double fd = (at(tp, x).value - at(tm, x).value) / (2 * h);
      const double fd1 = (at(tp, x).first - at(tm, x).first) / (2 * h);
      INFO("x = " << x << ", datum " << i);
      CHECK(v.value.derivatives()(i) == Approx(fd).margin(1e-8));
      CHECK(v.first.derivatives()(i) == Approx(fd1).margin(1e-7));
    }
    // The slope and curvature in x are those of the curve itself.
    const double h = 1e-6;
    CHECK(at(theta, x).first == Approx((at(theta, x + h).value - at(theta, x - h).value) / (2 * h)).margin(1e-7));
    CHECK(at(theta, x).second == Approx((at(theta, x + h).first - at(theta, x - h).first) / (2 * h)).margin(1e-6));
  }
}

TEST_CASE("B-spline gait equals the polynomial gait when its path is a cubic", "[gait][bspline]") {
  // The optimal step with its α_int point moved onto the Hermite cubic of the SS ends: the
  // thesis' quartic then degenerates to that cubic, which the B-spline reproduces.
  const GaitEvaluator poly = test::defaultGaitEvaluator();
  const GaitEvaluator spline = test::defaultGaitEvaluator(withBasis(1, 0, PathBasis::BSpline));
  GaitParameters p = test::optimalStep();
  const GaitMotion<double> mo = poly.evaluate(p).motion;
  const double a = 0.5 * (mo.alpha_iSS + mo.alpha_fSS);
  Vec5 q;
  q(0) = a;
  for (int j = 0; j < 4; ++j) {
    const PathCurve<double>& c = mo.ss_path[j];
    q(j + 1) = cubicHermite(mo.alpha_iSS, c(mo.alpha_iSS).value, c(mo.alpha_iSS).first, mo.alpha_fSS,
                            c(mo.alpha_fSS).value, c(mo.alpha_fSS).first)(a).value;
  }
  REQUIRE(q(4) < 0.0);  // the human-like knee branch of the α_int inverse kinematics
  REQUIRE(q(4) > -M_PI);
  // Swing foot relative to the hip from δ3, δ4 (the inverse of leg2InverseKinematics).
  const Model& m = poly.model();
  const double theta4 = a + q(1) + q(3) + 0.5 * M_PI;
  const double u = m.robot.l4 - m.robot.l5 * std::cos(q(4)), w = m.robot.l5 * std::sin(q(4));
  p(kDelta1Int) = q(1);
  p(kTheta3Int) = a + q(1) - q(2) + 0.5 * M_PI;  // (3.17)
  p(kX2rInt) = std::cos(theta4) * u - std::sin(theta4) * w;
  p(kZ2Int) = std::sin(theta4) * u + std::cos(theta4) * w - foot1FromHip(m, a, q(1))(1);
  const GaitEvaluation<double> ep = poly.evaluate(p), es = spline.evaluate(p);
  REQUIRE(ep.motion_computed);
  REQUIRE(es.motion.ss_path[0].pieces.size() == 2);
  CHECK(std::abs(ep.motion.ss_path[3].pieces[0].c[4]) < 1e-9);  // the quartic term vanished
  CHECK(es.failed_level == ep.failed_level);
  CHECK(es.C_Gamma == Approx(ep.C_Gamma).epsilon(1e-10));
  CHECK(es.W == Approx(ep.W).epsilon(1e-10));
  CHECK(es.T_SS == Approx(ep.T_SS).epsilon(1e-12));
  for (std::size_t k = 0; k < ep.g.size(); ++k) CHECK(es.g[k] == Approx(ep.g[k]).margin(1e-9));
  // Off the cubic, the bases give different gaits from the same parameters.
  p(kZ2Int) += 0.01;
  CHECK(std::abs(spline.evaluate(p).C_Gamma - poly.evaluate(p).C_Gamma) > 1.0);
}

TEST_CASE("exact gradients of a B-spline gait equal finite differences", "[gait][bspline]") {
  const GaitEvaluator coarse = test::defaultGaitEvaluator();
  const GaitEvaluator ev = test::defaultGaitEvaluator(withBasis(3, 1, PathBasis::BSpline));
  const Parameterisation& par = ev.options().parameterisation;
  GaitParameters p = toRicherParameterisation(coarse, test::optimalStep(), par);
  p(par.ssPointIndex(0)) += 0.02;
  p(par.dsPointIndex(0)) -= 0.01;
  const GaitGradient grad = ev.evaluateWithGradient(p);
  REQUIRE(grad.value.motion_computed);
  std::vector<test::GradientOutput> outputs = {
      {"C_Gamma", [](const GaitEvaluation<double>& e) { return e.C_Gamma; }, grad.dC_Gamma},
      {"speed", [](const GaitEvaluation<double>& e) { return e.speed; }, grad.dspeed},
  };
  for (const ConstraintGroup& g : ev.layout().groups())
    for (int k = g.offset; k < g.offset + g.count; ++k) {
      if (grad.value.state[k] != ConstraintState::Defined) continue;
      outputs.push_back({g.name, [k](const GaitEvaluation<double>& e) { return e.g[k]; },
                         grad.dg.row(k).transpose()});
    }
  const test::GradientCheck r =
      test::checkGradient(ev, p, outputs, [](const std::string& s) { return s; });
  INFO(r.failures);
  CHECK(r.failed == 0);
  CHECK(r.checked > 0.9 * (r.checked + r.skipped));
  // The extra points move the criterion.
  CHECK(std::abs(grad.dC_Gamma(par.ssPointIndex(0))) > 1.0);
  CHECK(std::abs(grad.dC_Gamma(par.dsPointIndex(0))) > 1.0);
}

TEST_CASE("parameterisation basis key: read, written back, bad value named", "[gait][bspline]") {
  const auto parse = [](const std::string& text) {
    return parseParameterisation(YamlMap(parseYamlText(text, "gait.yaml"), "gait.yaml", ""),
                                 Landing::ZeroVelocity);
  };
  const Parameterisation b = parse("parameterisation: {ss_points: 5, ds_points: 2, basis: bspline}\n");
  CHECK(b.basis == PathBasis::BSpline);
  CHECK(b.ss_points == 5);
  CHECK(b.label() == "miossec+ss5+ds2+bspline");
  CHECK_FALSE(b.isThesis());
  CHECK(parse("parameterisation: {ss_points: 1, basis: polynomial}\n").isThesis());
  GaitOptions o;
  o.parameterisation = b;
  const std::string written = gaitYaml("robot.yaml", GaitParameters::Zero(b.size()), o, {});
  CHECK(written.find("parameterisation: {ss_points: 5, ds_points: 2, basis: bspline}") !=
        std::string::npos);
  CHECK(parse(written.substr(written.find("parameterisation:"))
                  .substr(0, written.substr(written.find("parameterisation:")).find('\n') + 1)) == b);
  try {
    parse("parameterisation: {ss_points: 3, basis: nurbs}\n");
    FAIL("no error");
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    CHECK(what.find("gait.yaml") != std::string::npos);
    CHECK(what.find("parameterisation.basis") != std::string::npos);
    CHECK(what.find("expected 'polynomial' or 'bspline', got 'nurbs'") != std::string::npos);
  }
  // A controller export needs one polynomial per output.
  const SplineData d(1);
  CHECK_THROWS_WITH(d.curve(PathBasis::BSpline).polynomial(),
                    Catch::Contains("basis: polynomial"));
  CHECK_NOTHROW(d.curve(PathBasis::Polynomial).polynomial());
}
