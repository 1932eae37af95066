#include "gaitopt/model/foot_on_ground.hpp"

#include <cmath>

#include "gaitopt/model/dynamics_pinned.hpp"

namespace gaitopt {

GroundProjection projectFoot2OnGround(const Model& model, const Vec5& q) {
  GroundProjection p;
  p.q = q;
  const Vec5 zero = Vec5::Zero();
  constexpr int kMaxSteps = 8;  // quadratic convergence: 2–3 steps from micrometres
  for (int k = 0; k <= kMaxSteps; ++k) {
    const PinnedTerms<double> t = pinnedTerms(model, p.q, zero);
    const double z2 = t.foot2(1);
    if (k == 0) p.height = z2;
    p.converged = std::abs(z2) <= kGroundProjectionTolerance;
    if (p.converged || k == kMaxSteps) break;
    const Vec5 J = t.D2.row(1).transpose();  // ∂z2/∂q
    const double JJ = J.squaredNorm();
    if (!(JJ > 0.0)) break;
    p.q -= J * (z2 / JJ);  // the least-norm Δq with J·Δq = −z2
  }
  p.max_change = (p.q - q).cwiseAbs().maxCoeff();
  return p;
}

}  // namespace gaitopt
