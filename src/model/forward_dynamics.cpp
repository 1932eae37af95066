#include "gaitopt/model/forward_dynamics.hpp"

#include <Eigen/Cholesky>
#include <cmath>

#include "gaitopt/model/dynamics_pinned.hpp"

namespace gaitopt {

Vec5 forwardDynamicsSS(const Model& model, const Vec5& q, const Vec5& qd, const Vec4& gamma_star,
                       SignMode mode) {
  const PinnedTerms<double> t = pinnedTerms(model, q, qd);
  const Vec4 gamma = gamma_star - frictionTorque(model, jointSpeeds(qd), mode);
  const Vec5 rhs = model.D_Gamma * gamma - t.C - t.G;
  return t.A.llt().solve(rhs);
}

double pinnedEnergy(const Model& model, const Vec5& q, const Vec5& qd) {
  const PinnedTerms<double> t = pinnedTerms(model, q, qd);
  return 0.5 * qd.dot(t.A * qd) + model.total_mass * model.gravity * t.com(1);
}

PinnedState simulateSS(const Model& model, const PinnedState& x0, const TorqueLaw& torque,
                       double duration, double dt, SignMode mode) {
  const auto derivative = [&](double t, const PinnedState& x) {
    return PinnedState{x.qd, forwardDynamicsSS(model, x.q, x.qd, torque(t, x), mode)};
  };
  const auto step = [](const PinnedState& x, const PinnedState& k, double h) {
    return PinnedState{x.q + h * k.q, x.qd + h * k.qd};
  };
  const int n = static_cast<int>(std::ceil(duration / dt - 1e-9));
  const double h = duration / n;
  PinnedState x = x0;
  for (int i = 0; i < n; ++i) {
    const double t = i * h;
    const PinnedState k1 = derivative(t, x);
    const PinnedState k2 = derivative(t + 0.5 * h, step(x, k1, 0.5 * h));
    const PinnedState k3 = derivative(t + 0.5 * h, step(x, k2, 0.5 * h));
    const PinnedState k4 = derivative(t + h, step(x, k3, h));
    x.q += h / 6.0 * (k1.q + 2.0 * k2.q + 2.0 * k3.q + k4.q);
    x.qd += h / 6.0 * (k1.qd + 2.0 * k2.qd + 2.0 * k3.qd + k4.qd);
  }
  return x;
}

}  // namespace gaitopt
