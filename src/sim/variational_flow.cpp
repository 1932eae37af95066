#include "gaitopt/sim/variational_flow.hpp"

#include <cmath>
#include <stdexcept>

namespace gaitopt {
namespace {

// Relative size of the directional-difference step: truncation O(ε²) ≈ 1e-12 and round-off
// O(1e-16/ε) ≈ 1e-10 of ‖f‖, far below the 1e-6 the Jacobian is checked to.
constexpr double kDirectionalStep = 1e-6;
// Absolute tolerance of the sensitivities (O(1) entries): the difference quotients carry
// ~1e-10 relative noise, so the state's 1e-12-level error test on them would stall CVODE; at
// 1e-8 the walking Jacobian agrees with Richardson differences to 1e-7 relative and costs a
// third of the 20-step differences (1e-10: 4 times the differences' time).
constexpr double kSensitivityAbsolute = 1e-8;

// f(x) and fₓ S column by column: (f(x + ε s) − f(x − ε s)) / 2ε, ε scaled to the state.
void augmentedRhs(const CvodeIntegrator::Rhs& f, int n, int m, double t, const Eigen::VectorXd& y,
                  Eigen::VectorXd& ydot) {
  const Eigen::VectorXd x = y.head(n);
  Eigen::VectorXd fx, fp, fm;
  f(t, x, fx);
  ydot.resize(n + n * m);
  ydot.head(n) = fx;
  const double scale = kDirectionalStep * (1.0 + x.lpNorm<Eigen::Infinity>());
  for (int j = 0; j < m; ++j) {
    const Eigen::VectorXd s = y.segment(n + j * n, n);
    const double size = s.lpNorm<Eigen::Infinity>();
    if (size == 0.0) {
      ydot.segment(n + j * n, n).setZero();
      continue;
    }
    const double eps = scale / size;
    f(t, x + eps * s, fp);
    f(t, x - eps * s, fm);
    ydot.segment(n + j * n, n) = (fp - fm) / (2.0 * eps);
  }
}

}  // namespace

Eigen::MatrixXd centralJacobian(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& F,
                                const Eigen::VectorXd& x, double h) {
  Eigen::MatrixXd J;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd xp = x, xm = x;
    xp(i) += h;
    xm(i) -= h;
    const Eigen::VectorXd d = (F(xp) - F(xm)) / (2.0 * h);
    if (i == 0) J.resize(d.size(), x.size());
    J.col(i) = d;
  }
  return J;
}

PhaseEnd flowWithSensitivity(const HybridPhase& phase, const SensitiveState& start, double t_end,
                             const CvodeTolerances& tol) {
  const int n = static_cast<int>(start.x.size()), m = static_cast<int>(start.S.cols());
  CvodeTolerances aug = tol;
  aug.absolute_per_component.setConstant(n + n * m, kSensitivityAbsolute);
  aug.absolute_per_component.head(n).setConstant(tol.absolute);
  CvodeIntegrator cv(
      n + n * m,
      [&](double t, const Eigen::VectorXd& y, Eigen::VectorXd& f) {
        augmentedRhs(phase.field, n, m, t, y, f);
      },
      phase.event ? 1 : 0,
      [&](double, const Eigen::VectorXd& y, Eigen::VectorXd& g) {
        g.resize(1);
        g(0) = phase.event(y.head(n));
      },
      aug);
  Eigen::VectorXd y0(n + n * m);
  y0 << start.x, Eigen::Map<const Eigen::VectorXd>(start.S.data(), n * m);
  cv.reset(start.t, y0);
  const CvodeIntegrator::Result r = cv.advance(t_end);
  PhaseEnd end;
  end.event = r.root == 0;
  end.state.t = r.t;
  end.state.x = r.y.head(n);
  end.state.S = Eigen::Map<const Eigen::MatrixXd>(r.y.data() + n, n, m);
  if (end.event) {
    // Saltation of a state-triggered event time: dτ = −gₓ S / (gₓ f).
    const Eigen::RowVectorXd gx = centralJacobian(
        [&](const Eigen::VectorXd& x) { return Eigen::VectorXd::Constant(1, phase.event(x)); },
        end.state.x, 1e-7);
    Eigen::VectorXd f;
    phase.field(end.state.t, end.state.x, f);
    const double rate = gx.dot(f);
    if (std::abs(rate) < 1e-12) throw std::runtime_error("event crossed tangentially");
    end.state.S -= f * (gx * end.state.S) / rate;
  }
  return end;
}

}  // namespace gaitopt
