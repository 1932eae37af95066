// The richer parameterisation: refining a thesis step keeps its motion, and exact gradients
// hold for the extra parameters too.
#include <catch2/catch.hpp>
#include <cmath>

#include "gaitopt/gait/richer_parameterisation.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "test_gait_support.hpp"

using namespace gaitopt;

namespace {
GaitOptions richer(int ss, int ds) {
  GaitOptions o = test::viscousOptions();
  o.parameterisation.ss_points = ss;
  o.parameterisation.ds_points = ds;
  return o;
}
}  // namespace

TEST_CASE("parameter names and indices of a richer parameterisation", "[richer]") {
  const Parameterisation par = richer(3, 2).parameterisation;
  CHECK(par.size() == 17 + 8 + 4);
  const std::vector<std::string> n = par.names();
  CHECK(n[par.ssPointIndex(1)] == "delta1_int");  // the middle point is the thesis' α_int
  CHECK(n[par.ssPointIndex(0)] == "delta1_ss25");
  CHECK(n[par.ssPointIndex(2) + 3] == "delta4_ss75");  // extra points carry joint angles
  CHECK(n[par.dsPointIndex(1) + 1] == "theta3_ds67");
  CHECK(par.label() == "miossec+ss3+ds2");
}

TEST_CASE("refining a thesis step to a richer parameterisation keeps the motion", "[richer]") {
  const GaitEvaluator coarse = test::defaultGaitEvaluator();
  const GaitParameters p = test::optimalStep();
  const GaitEvaluation<double> e0 = coarse.evaluate(p);
  for (const auto& [ss, ds] : {std::pair{3, 0}, std::pair{1, 2}, std::pair{5, 1}}) {
    const GaitEvaluator fine = test::defaultGaitEvaluator(richer(ss, ds));
    const GaitParameters q = toRicherParameterisation(coarse, p, fine.options().parameterisation);
    REQUIRE(q.size() == fine.numParameters());
    const GaitEvaluation<double> e1 = fine.evaluate(q);
    INFO("ss_points " << ss << ", ds_points " << ds);
    CHECK(e1.failed_level == e0.failed_level);
    CHECK(e1.C_Gamma == Approx(e0.C_Gamma).epsilon(1e-9));
    CHECK(e1.T_SS == Approx(e0.T_SS).epsilon(1e-11));
    CHECK(e1.speed == Approx(e0.speed).epsilon(1e-11));
  }
}

TEST_CASE("exact gradients of a richer parameterisation equal finite differences", "[richer]") {
  const GaitEvaluator coarse = test::defaultGaitEvaluator();
  const GaitEvaluator fine = test::defaultGaitEvaluator(richer(3, 1));
  GaitParameters q = toRicherParameterisation(coarse, test::optimalStep(), fine.options().parameterisation);
  // Move the extra points off the coarse polynomial so the new parameters matter.
  const Parameterisation& par = fine.options().parameterisation;
  q(par.ssPointIndex(0)) += 0.02;
  q(par.dsPointIndex(0)) -= 0.01;
  const GaitGradient g = fine.evaluateWithGradient(q);
  REQUIRE(g.value.motion_computed);
  int checked = 0;
  for (int i = 0; i < fine.numParameters(); ++i) {
    const double h = 1e-6 * std::max(1.0, std::abs(q(i)));
    GaitParameters qp = q, qm = q;
    qp(i) += h;
    qm(i) -= h;
    const GaitEvaluation<double> ep = fine.evaluate(qp), em = fine.evaluate(qm);
    const double fd = (ep.C_Gamma - em.C_Gamma) / (2 * h);
    INFO("parameter " << par.names()[i]);
    CHECK(std::abs(g.dC_Gamma(i) - fd) <= 1e-5 * std::max(1.0, std::abs(fd)));
    const int entry = fine.layout()[kTorqueSS].offset + 8 * 10;  // Γ1* − limit at an SS node
    const double fdg = (ep.g[entry] - em.g[entry]) / (2 * h);
    CHECK(std::abs(g.dg(entry, i) - fdg) <= 1e-5 * std::max(1.0, std::abs(fdg)));
    ++checked;
  }
  CHECK(checked == 17 + 4 + 4 + 2);
  // The extra parameters do move the criterion.
  CHECK(std::abs(g.dC_Gamma(par.ssPointIndex(0))) > 1.0);
  CHECK(std::abs(g.dC_Gamma(par.dsPointIndex(0))) > 1.0);
}

TEST_CASE("the richer parameterisation is exact also where the swing knee hyperextends", "[richer]") {
  // Chesse's Ipopt optimum passes through δ4 < −π during single support: a swing-foot position
  // with the human-like IK branch would give another configuration there, joint angles do not.
  const GaitFile g = loadGaitFile(test::sourcePath("configs/gait/chesse_0.85_ipopt.yaml"));
  const GaitEvaluator coarse(g.robot, g.options, g.model_options);
  const GaitEvaluation<double> e0 = coarse.evaluate(g.parameters);
  double min_delta4 = 0.0;
  for (int k = 0; k <= 20; ++k)
    min_delta4 = std::min(min_delta4, e0.motion.ss_path[3](e0.motion.alpha_iSS + k / 20.0 *
                                                              (e0.motion.alpha_fSS - e0.motion.alpha_iSS)).value);
  CHECK(min_delta4 < -M_PI);  // the case this test is about
  GaitOptions rich = g.options;
  rich.parameterisation.ss_points = 3;
  rich.parameterisation.ds_points = 1;
  const GaitEvaluator fine(g.robot, rich, g.model_options);
  const GaitEvaluation<double> e1 =
      fine.evaluate(toRicherParameterisation(coarse, g.parameters, rich.parameterisation));
  CHECK(e1.C_Gamma == Approx(e0.C_Gamma).epsilon(1e-9));
}
