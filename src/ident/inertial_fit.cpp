#include "gaitopt/ident/inertial_fit.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

namespace gaitopt {

const std::array<const char*, kNumInertialParameters> kInertialParameterNames = {
    "m_tibia", "h_tibia", "J_tibia", "m_femur", "h_femur", "J_femur",
    "m_trunk", "h_trunk", "J_trunk"};
const std::array<const char*, kNumInertialParameters> kInertialParameterUnits = {
    "kg", "kg·m", "kg·m²", "kg", "kg·m", "kg·m²", "kg", "kg·m", "kg·m²"};

namespace {

constexpr std::array<int, 5> kClassOfLink = {0, 1, 2, 1, 0};  // tibia, femur, trunk, femur, tibia

// CoM distance from the proximal joint as the dynamics see it (the trunk's shifted).
double comOffset(const RobotParams& r, int link) {
  return r.s[link] + (link == 2 ? r.trunk_com_shift : 0.0);
}

Eigen::Vector3d linkParameters(const RobotParams& r, int link) {
  const double m = r.mass[link], s = comOffset(r, link);
  return {m, m * s, r.inertia[link] + m * s * s};
}

double linkLength(const RobotParams& r, int link) {
  const std::array<double, 5> l{r.l1, r.l2, r.trunk_length, r.l4, r.l5};
  return l[link];
}

// One barrier term −log g(δ) with g a constraint of a link's (m, h, J): value, gradient and
// Hessian in the link's three parameters.
struct Constraint {
  int link, kind;  // kind 0: m > 0, 1: m J − h² > 0, 2: s > 0, 3: s < length
  std::string name;
};

std::vector<Constraint> constraints() {
  std::vector<Constraint> out;
  for (int i = 0; i < 5; ++i) {
    const std::string n = std::to_string(i + 1);
    const std::string l = i == 2 ? "trunk_length" : "l" + n;
    out.push_back({i, 0, "m" + n + " > 0"});
    out.push_back({i, 1, "I" + n + " > 0"});
    out.push_back({i, 2, "s" + n + " > 0"});
    out.push_back({i, 3, "s" + n + " < " + l});
  }
  return out;
}

// g at the link parameters x = (m, h, J), with its gradient and Hessian.
double constraintValue(const Constraint& c, const RobotParams& r, const Eigen::Vector3d& x,
                       Eigen::Vector3d& grad, Eigen::Matrix3d& hess) {
  hess.setZero();
  const double shift = c.link == 2 ? r.trunk_com_shift : 0.0;  // file s = h/m − shift
  switch (c.kind) {
    case 0: grad = {1, 0, 0}; return x(0);
    case 1:
      grad = {x(2), -2.0 * x(1), x(0)};
      hess(0, 2) = hess(2, 0) = 1.0;
      hess(1, 1) = -2.0;
      return x(0) * x(2) - x(1) * x(1);
    case 2: grad = {-shift, 1, 0}; return x(1) - shift * x(0);
    default: {
      const double l = linkLength(r, c.link) + shift;
      grad = {l, -1, 0};
      return l * x(0) - x(1);
    }
  }
}

Eigen::VectorXd scales() {
  Eigen::VectorXd s(kNumInertialParameters);
  for (int k = 0; k < kNumInertialParameters; ++k) s(k) = inertialScale(k);
  return s;
}

// Barrier value, gradient and Hessian of every constraint at δ; +inf when infeasible.
double barrier(const RobotParams& r, const std::vector<Constraint>& cs, const Eigen::VectorXd& d,
               Eigen::VectorXd* grad, Eigen::MatrixXd* hess) {
  double value = 0.0;
  for (const Constraint& c : cs) {
    const int k = 3 * kClassOfLink[c.link];
    const Eigen::Vector3d x = linkParameters(r, c.link) + d.segment<3>(k);
    Eigen::Vector3d g;
    Eigen::Matrix3d h;
    const double v = constraintValue(c, r, x, g, h);
    if (!(v > 0.0)) return INFINITY;
    value -= std::log(v);
    if (grad) grad->segment<3>(k) -= g / v;
    if (hess) hess->block<3, 3>(k, k) += g * g.transpose() / (v * v) - h / v;
  }
  return value;
}

}  // namespace

double inertialScale(int k) { return k % 3 == 0 ? 1.0 : 0.1; }

Eigen::VectorXd inertialParameters(const RobotParams& robot) {
  Eigen::VectorXd p(kNumInertialParameters);
  for (int c = 0; c < 3; ++c) p.segment<3>(3 * c) = linkParameters(robot, c);
  return p;
}

RobotParams withInertialChange(RobotParams r, const Eigen::VectorXd& delta) {
  for (int i = 0; i < 5; ++i) {
    const Eigen::Vector3d x = linkParameters(r, i) + delta.segment<3>(3 * kClassOfLink[i]);
    const double s = x(1) / x(0);
    r.mass[i] = x(0);
    r.s[i] = s - (i == 2 ? r.trunk_com_shift : 0.0);
    r.inertia[i] = x(2) - x(0) * s * s;
  }
  return r;
}

Eigen::VectorXd BaseParameters::values(const Eigen::VectorXd& p) const {
  Eigen::VectorXd b(rank);
  for (int i = 0; i < rank; ++i) {
    b(i) = p(independent[i]);
    for (std::size_t j = 0; j < dependent.size(); ++j) b(i) += regroup(i, j) * p(dependent[j]);
  }
  return b;
}

std::string BaseParameters::label(int i) const {
  std::string s = kInertialParameterNames[independent[i]];
  for (std::size_t j = 0; j < dependent.size(); ++j) {
    const double k = regroup(i, j);
    if (std::abs(k) < 1e-9) continue;
    char b[64];
    std::snprintf(b, sizeof b, " %c %.4g %s", k < 0 ? '-' : '+', std::abs(k),
                  kInertialParameterNames[dependent[j]]);
    s += b;
  }
  return s;
}

BaseParameters baseParameters(const Eigen::MatrixXd& Y, double relative_tolerance) {
  const Eigen::VectorXd s = scales();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Y * s.asDiagonal());
  qr.setThreshold(relative_tolerance);
  BaseParameters b;
  b.rank = static_cast<int>(qr.rank());
  const auto& perm = qr.colsPermutation().indices();
  for (int i = 0; i < kNumInertialParameters; ++i)
    (i < b.rank ? b.independent : b.dependent).push_back(perm(i));
  const Eigen::MatrixXd R = qr.matrixR().topRows(b.rank).template triangularView<Eigen::Upper>();
  const Eigen::MatrixXd K = R.leftCols(b.rank).triangularView<Eigen::Upper>().solve(
      R.rightCols(kNumInertialParameters - b.rank));
  b.regroup.resize(b.rank, b.dependent.size());
  for (int i = 0; i < b.rank; ++i)
    for (std::size_t j = 0; j < b.dependent.size(); ++j)  // back to unscaled parameters
      b.regroup(i, j) = K(i, j) * s(b.independent[i]) / s(b.dependent[j]);
  return b;
}

ConsistentFit consistentLeastSquares(const Eigen::MatrixXd& Y, const Eigen::VectorXd& r0,
                                     const RobotParams& robot, double lambda) {
  const std::vector<Constraint> cs = constraints();
  const Eigen::VectorXd s = scales();
  const Eigen::MatrixXd H0 =
      2.0 * (Y.transpose() * Y + lambda * s.cwiseInverse().cwiseAbs2().asDiagonal().toDenseMatrix());
  const Eigen::VectorXd g0 = 2.0 * Y.transpose() * r0;
  const auto objective = [&](const Eigen::VectorXd& d) {
    return (r0 + Y * d).squaredNorm() + lambda * d.cwiseQuotient(s).squaredNorm();
  };
  ConsistentFit fit;
  const Eigen::VectorXd unconstrained = H0.ldlt().solve(-g0);
  for (const Constraint& c : cs) {
    Eigen::Vector3d g;
    Eigen::Matrix3d h;
    const Eigen::Vector3d x =
        linkParameters(robot, c.link) + unconstrained.segment<3>(3 * kClassOfLink[c.link]);
    if (!(constraintValue(c, robot, x, g, h) > 0.0)) fit.active.push_back(c.name);
  }
  Eigen::VectorXd d = Eigen::VectorXd::Zero(kNumInertialParameters);
  if (fit.active.empty()) {  // the constraints do not bind: the LS minimiser is the answer
    fit.delta = unconstrained;
    return fit;
  }
  // Barrier weight μ from 1e-3 of the starting objective down by 10 per stage: the final
  // duality gap (μ × number of constraints) is negligible next to the objective.
  const double q0 = std::max(objective(d), 1e-12);
  for (double mu = 1e-3 * q0; mu > 1e-12 * q0; mu *= 0.1) {
    const auto total = [&](const Eigen::VectorXd& x) {
      return objective(x) + mu * barrier(robot, cs, x, nullptr, nullptr);
    };
    for (int it = 0; it < 50; ++it) {
      Eigen::VectorXd grad = H0 * d + g0;
      Eigen::MatrixXd hess = H0;
      Eigen::VectorXd bg = Eigen::VectorXd::Zero(kNumInertialParameters);
      Eigen::MatrixXd bh = Eigen::MatrixXd::Zero(kNumInertialParameters, kNumInertialParameters);
      barrier(robot, cs, d, &bg, &bh);
      grad += mu * bg;
      hess += mu * bh;
      const Eigen::VectorXd step = hess.ldlt().solve(-grad);
      const double decrement = -grad.dot(step);
      if (decrement < 1e-12 * q0) break;
      const double f = total(d);
      double t = 1.0;  // backtracking: feasible (finite barrier) and Armijo decrease
      while (t > 1e-12 && !(total(d + t * step) <= f - 0.25 * t * decrement)) t *= 0.5;
      if (t <= 1e-12) break;
      d += t * step;
    }
  }
  fit.delta = d;
  return fit;
}

}  // namespace gaitopt
