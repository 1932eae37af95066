// The solutions both impact solvers return: names, the contact state after impact, and the
// building and classification of the solution set.
#include "gaitopt/impact/impact_result.hpp"

#include <algorithm>
#include <cmath>

namespace gaitopt {

const char* toString(ImpactModelKind k) {
  return k == ImpactModelKind::Algebraic ? "algebraic" : "differential";
}

const char* toString(ImpactStatus s) {
  switch (s) {
    case ImpactStatus::Unique: return "unique";
    case ImpactStatus::Indeterminate: return "indeterminate";
    case ImpactStatus::Inconsistent: return "inconsistent";
    case ImpactStatus::Accumulation: return "accumulation";
  }
  return "?";
}

ImpactBehaviour contactState(const Eigen::Vector4d& V, double speed, double tolerance) {
  const double eps = tolerance * speed;
  const auto slip1 = V(0) > 0.0 ? Foot1Behaviour::SlipPlus : Foot1Behaviour::SlipMinus;
  const auto slip2 = V(2) > 0.0 ? Foot2Behaviour::SlipPlus : Foot2Behaviour::SlipMinus;
  ImpactBehaviour b;
  b.foot1 = V(1) > eps ? Foot1Behaviour::Lift
                       : (std::abs(V(0)) <= eps ? Foot1Behaviour::Stick : slip1);
  b.foot2 = std::abs(V(2)) <= eps ? Foot2Behaviour::Stick : slip2;
  return b;
}

namespace detail {

ImpactScales impactScales(const ImpactSystem<double>& system) {
  const double speed = system.V_minus.tail<2>().norm();
  return {speed, speed / system.W.diagonal().maxCoeff()};
}

void completeSolution(const ImpactSystem<double>& system, const Eigen::Vector4d& I,
                      const ImpactOptions& options, ImpactSolution& s) {
  s.impulse1 = I.head<2>();
  s.impulse2 = I.tail<2>();
  s.Xd_plus = system.Xd_minus + system.Ainv_Dt * I;  // (2.1)
  s.V_plus = system.V_minus + system.W * I;           // (2.13)
  s.energy_loss = 0.5 * system.Xd_minus.dot(system.A * system.Xd_minus) -
                  0.5 * s.Xd_plus.dot(system.A * s.Xd_plus);
  s.contact = contactState(s.V_plus, impactScales(system).speed, options.tolerance);
}

bool sameOutcome(const ImpactSolution& a, const ImpactSolution& b, double impulse_tolerance,
                 double relative_tolerance) {
  const double d = std::max((a.impulse1 - b.impulse1).cwiseAbs().maxCoeff(),
                            (a.impulse2 - b.impulse2).cwiseAbs().maxCoeff());
  const double size = std::max(a.impulse1.norm() + a.impulse2.norm(),
                               b.impulse1.norm() + b.impulse2.norm());
  return d <= std::max(impulse_tolerance, relative_tolerance * size);
}

void addDistinctSolution(std::vector<ImpactSolution>& solutions, ImpactSolution s,
                         double impulse_tolerance, double relative_tolerance) {
  for (ImpactSolution& kept : solutions)
    if (sameOutcome(kept, s, impulse_tolerance, relative_tolerance)) {
      kept.boundary = true;
      return;
    }
  solutions.push_back(std::move(s));
}

ImpactStatus statusOf(const std::vector<ImpactSolution>& solutions, double impulse_tolerance,
                      double relative_tolerance) {
  if (solutions.empty()) return ImpactStatus::Inconsistent;
  bool accumulation = false;
  for (const ImpactSolution& s : solutions) {
    accumulation = accumulation || s.accumulation;
    if (!sameOutcome(s, solutions.front(), impulse_tolerance, relative_tolerance))
      return ImpactStatus::Indeterminate;
  }
  return accumulation ? ImpactStatus::Accumulation : ImpactStatus::Unique;
}

}  // namespace detail

}  // namespace gaitopt
