#include "gaitopt/sim/poincare.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace gaitopt {

Eigen::MatrixXd finiteDifferenceJacobian(const StepMap& P, const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& h) {
  const Eigen::Index n = x.size();
  Eigen::MatrixXd J(P(x).size(), n);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::VectorXd xp = x, xm = x;
    xp(i) += h(i);
    xm(i) -= h(i);
    J.col(i) = (P(xp) - P(xm)) / (2.0 * h(i));
  }
  return J;
}

PoincareLinearisation analyseJacobian(const Eigen::MatrixXd& J) {
  PoincareLinearisation r;
  r.jacobian = J;
  const Eigen::EigenSolver<Eigen::MatrixXd> es(J);
  std::vector<Eigen::Index> order(J.rows());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
    return std::abs(es.eigenvalues()(a)) > std::abs(es.eigenvalues()(b));
  });
  r.eigenvalues.resize(J.rows());
  for (Eigen::Index i = 0; i < J.rows(); ++i) r.eigenvalues(i) = es.eigenvalues()(order[i]);
  r.dominant_vector = es.eigenvectors().col(order[0]).normalized();
  return r;
}

PoincareLinearisation linearisePoincare(const StepMap& P, const Eigen::VectorXd& x,
                                        const Eigen::VectorXd& h) {
  PoincareLinearisation r = analyseJacobian(finiteDifferenceJacobian(P, x, h));
  r.fixed_point_residual = (P(x) - x).lpNorm<Eigen::Infinity>();
  return r;
}

PoincareLinearisation linearisePoincareOrDifferences(
    const std::function<PoincareLinearisation()>& sensitivity, const StepMap& P,
    const Eigen::VectorXd& x, const Eigen::VectorXd& h, std::string& fallback) {
  try {
    return sensitivity();
  } catch (const IntegrationError& error) {
    fallback = error.what();
    return linearisePoincare(P, x, h);
  }
}

double powerIteration(const StepMap& P, const Eigen::VectorXd& x, const Eigen::VectorXd& dx_max,
                      int iterations, Eigen::VectorXd& vector) {
  const Eigen::VectorXd Px = P(x);
  vector = dx_max;
  double c = 0.0;
  for (int k = 0; k < iterations; ++k) {
    const Eigen::VectorXd g = P(x + vector) - Px;
    Eigen::Index j = 0;
    g.cwiseQuotient(dx_max).cwiseAbs().maxCoeff(&j);
    c = g(j) / dx_max(j);  // signed, (4.61)
    vector = g / c;
  }
  return c;
}

Eigen::VectorXd walkingCycleState(const GaitMotion<double>& mo) {
  Eigen::VectorXd x(10);
  x.head<5>() = mo.q_iSS;
  x(5) = mo.alphadot_iSS;
  for (int j = 0; j < 4; ++j) x(6 + j) = mo.ss_path[j](mo.q_iSS(0)).first * mo.alphadot_iSS;
  return x;
}

StepMap walkingStepMap(const GaitEvaluation<double>& e, const Model& controller,
                       const Model& plant, const WalkRequest& base,
                       const TouchdownMap& touchdown) {
  return [&e, &controller, &plant, base, touchdown](const Eigen::VectorXd& x) {
    WalkRequest req = base;
    req.steps = 1;
    req.use_initial_state = true;
    req.q_init = x.head<5>();
    req.qd_init = x.tail<5>();
    req.sample_rate = 1.0;  // no samples needed between events
    const WalkResult r = simulateWalk(e, controller, plant, req, touchdown);
    if (r.outcome != WalkOutcome::Completed)
      throw std::runtime_error(std::string("walking step map: ") + outcomeName(r.outcome) + ": " +
                               r.message);
    Eigen::VectorXd y(10);
    y << r.q_end, r.qd_end;
    return y;
  };
}

}  // namespace gaitopt
