// C_Γ as a sum of squares (GaitEvaluation::torque_residuals) and its Gauss–Newton Hessian
// 2 JᵀJ: the residuals reproduce C_Γ and its exact gradient, their Jacobian agrees with
// central differences, and the Hessian of the exact gradient (forward differences) is the
// Gauss–Newton part plus the residuals' own curvature Σ 2 r_i ∇²r_i.
#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/opt/gait_problem.hpp"
#include "test_gradient_check.hpp"
#include "test_support.hpp"

using gaitopt::GaitParameters;
using gaitopt::MatrixX;
using gaitopt::VectorX;
using gaitopt::test::sourcePath;

namespace {

struct Case {
  std::string config, gait;
};

// The default problem at its shipped optimum, and Chessé's robot at its own (a DS whose force
// split switches branch: residuals on the DS pieces' grids).
std::vector<Case> cases() {
  return {{"configs/default.yaml", "configs/gait/default_step.yaml"},
          {"configs/chesse_0.85.yaml", "configs/gait/chesse_0.85.yaml"}};
}

gaitopt::GaitEvaluator evaluatorOf(const Case& c) {
  const gaitopt::OptimizeConfig config = gaitopt::loadOptimizeConfig(sourcePath(c.config));
  return gaitopt::GaitEvaluator(config.robot, config.options, config.model_options);
}

Eigen::Map<const VectorX> residuals(const gaitopt::GaitEvaluation<double>& e) {
  return {e.torque_residuals.data(), static_cast<Eigen::Index>(e.torque_residuals.size())};
}

}  // namespace

TEST_CASE("gauss-newton: C_Gamma is the sum of its squared residuals, its gradient 2 J^T r",
          "[gauss_newton]") {
  for (const Case& c : cases()) {
    const gaitopt::GaitEvaluator ev = evaluatorOf(c);
    const GaitParameters p = gaitopt::loadGaitFile(sourcePath(c.gait)).parameters;
    const gaitopt::GaitGradient g = ev.evaluateWithGradient(p);
    INFO(c.gait << ": " << g.value.torque_residuals.size() << " residuals, C_Gamma "
                << g.value.C_Gamma << ", DS switches " << g.value.ds_pieces.switch_times.size());
    REQUIRE(g.value.motion_computed);
    REQUIRE(g.dtorque_residuals.rows() == static_cast<Eigen::Index>(g.value.torque_residuals.size()));
    const VectorX r = residuals(g.value);
    CHECK(std::abs(r.squaredNorm() - g.value.C_Gamma) <= 1e-12 * g.value.C_Gamma);
    const VectorX grad = 2.0 * g.dtorque_residuals.transpose() * r;
    CHECK((grad - g.dC_Gamma).norm() <= 1e-10 * g.dC_Gamma.norm());
  }
}

namespace {

// The configured start of the default problem: inside every constraint level, so that the
// differences do not cross the evaluator's verdict (the optimum's active rows would).
GaitParameters startOf(const Case& c, const gaitopt::GaitEvaluator& ev) {
  return gaitopt::configuredInitialGuess(gaitopt::loadOptimizeConfig(sourcePath(c.config)),
                                         ev.model());
}

}  // namespace

TEST_CASE("gauss-newton: the residuals' Jacobian agrees with central differences",
          "[gauss_newton]") {
  const Case c = cases().front();
  const gaitopt::GaitEvaluator ev = evaluatorOf(c);
  const GaitParameters p = startOf(c, ev);
  const gaitopt::GaitGradient g = ev.evaluateWithGradient(p);
  std::vector<gaitopt::test::GradientOutput> outputs;
  for (std::size_t i = 0; i < g.value.torque_residuals.size(); ++i)
    outputs.push_back({"r" + std::to_string(i),
                       [i](const gaitopt::GaitEvaluation<double>& e) {
                         return i < e.torque_residuals.size() ? e.torque_residuals[i] : NAN;
                       },
                       g.dtorque_residuals.row(static_cast<Eigen::Index>(i)).transpose()});
  const gaitopt::test::GradientCheck check =
      gaitopt::test::checkGradient(ev, p, outputs, [](const std::string&) { return "r"; });
  INFO(check.failures << "worst " << check.worst << " at " << check.worst_what);
  CHECK(check.failed == 0);
  CHECK(check.checked > 0);
  CHECK(check.skipped <= check.checked / 100);
}

// H_FD s = (∇C(x + h s) − ∇C(x)) / h against 2 Jᵀ(J s) + 2 (J(x + h s) − J(x))ᵀ r / h, the
// second term being the residual curvature the Gauss–Newton model leaves out, on the
// scaled unit directions. The two terms nearly cancel in some directions (C_Γ's residuals are
// not small): the mismatch is measured against the larger of them.
TEST_CASE("gauss-newton: the exact gradient's differences split into 2 J^T J and the residual curvature",
          "[gauss_newton]") {
  const Case c = cases().front();
  const gaitopt::GaitEvaluator ev = evaluatorOf(c);
  const GaitParameters p = startOf(c, ev);
  const gaitopt::Parameterisation& par = ev.options().parameterisation;
  const gaitopt::GaitGradient g0 = ev.evaluateWithGradient(p);
  const VectorX r0 = residuals(g0.value);
  const GaitParameters scales = gaitopt::parameterScales(par);
  double worst = 0.0, gn_ratio = 0.0;
  for (int j = 0; j < par.size(); ++j) {
    if (!par.isUsed(j)) continue;
    const double h = 1e-6;
    const VectorX s = scales(j) * VectorX::Unit(par.size(), j);
    const gaitopt::GaitGradient g1 = ev.evaluateWithGradient(p + h * s);
    REQUIRE(g1.dtorque_residuals.rows() == g0.dtorque_residuals.rows());
    const VectorX hessian_s = (g1.dC_Gamma - g0.dC_Gamma) / h;
    const VectorX gauss_newton_s = 2.0 * g0.dtorque_residuals.transpose() * (g0.dtorque_residuals * s);
    const VectorX curvature_s = 2.0 * (g1.dtorque_residuals - g0.dtorque_residuals).transpose() * r0 / h;
    const double size = std::max({1.0, gauss_newton_s.norm(), curvature_s.norm()});
    worst = std::max(worst, (hessian_s - gauss_newton_s - curvature_s).norm() / size);
    gn_ratio = std::max(gn_ratio, gauss_newton_s.norm() / std::max(1.0, hessian_s.norm()));
  }
  INFO("worst relative mismatch " << worst << ", largest |GN s| / |H s| " << gn_ratio);
  // Forward differences with h = 1e-6 (scaled): the O(h) terms of both sides.
  CHECK(worst <= 1e-4);
}

TEST_CASE("gauss-newton: the cost terms' Hessians", "[gauss_newton]") {
  const Case c = cases().front();
  const gaitopt::GaitEvaluator ev = evaluatorOf(c);
  const GaitParameters p = gaitopt::loadGaitFile(sourcePath(c.gait)).parameters;
  const gaitopt::Parameterisation& par = ev.options().parameterisation;
  gaitopt::GaitEvaluationCache cache(ev);
  const double scale = 1e4;
  SECTION("C_Gamma: 2 J^T J / scale, symmetric positive semi-definite") {
    gaitopt::NlpProblem problem(gaitopt::gaitVariables(ev.model(), p, par));
    problem.addCost(gaitopt::makeCriterionCost(cache, gaitopt::Criterion::Torque, scale));
    REQUIRE(problem.hasCostHessian());
    MatrixX h;
    REQUIRE(problem.costHessian(p, h));
    const gaitopt::GaitGradient g = ev.evaluateWithGradient(p);
    const MatrixX expected = 2.0 / scale * g.dtorque_residuals.transpose() * g.dtorque_residuals;
    CHECK((h - expected).cwiseAbs().maxCoeff() <= 1e-12 * expected.cwiseAbs().maxCoeff());
    CHECK((h - h.transpose()).cwiseAbs().maxCoeff() == 0.0);
    const double smallest = Eigen::SelfAdjointEigenSolver<MatrixX>(h).eigenvalues().minCoeff();
    CHECK(smallest >= -1e-12 * h.cwiseAbs().maxCoeff());
  }
  SECTION("W and C_E: no sum of squares, no Hessian") {
    for (gaitopt::Criterion k : {gaitopt::Criterion::Work, gaitopt::Criterion::Energy}) {
      gaitopt::NlpProblem problem(gaitopt::gaitVariables(ev.model(), p, par));
      problem.addCost(gaitopt::makeCriterionCost(cache, k, scale));
      CHECK_FALSE(problem.hasCostHessian());
    }
  }
  SECTION("distance: exact, equal to the differences of its gradient") {
    gaitopt::NlpProblem problem(gaitopt::gaitVariables(ev.model(), p, par));
    const GaitParameters ref = p + 0.1 * gaitopt::parameterScales(par);
    problem.addCost(gaitopt::makeDistanceCost(ref, par));
    REQUIRE(problem.hasCostHessian());
    MatrixX h;
    REQUIRE(problem.costHessian(p, h));
    const int n = static_cast<int>(p.size());
    VectorX g0, g1;
    REQUIRE(problem.costGradient(p, g0));
    for (int j = 0; j < n; ++j) {
      const double step = 1e-3 * std::max(1.0, std::abs(p(j)));
      REQUIRE(problem.costGradient(p + step * VectorX::Unit(n, j), g1));
      CHECK(((g1 - g0) / step - h.col(j)).cwiseAbs().maxCoeff() <= 1e-6 * h.cwiseAbs().maxCoeff());
    }
  }
}
