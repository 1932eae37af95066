#pragma once
// Whether a single support will carry the robot over its stance foot, from the gait's own zero
// dynamics. The angular momentum about the stance foot σ changes only by gravity's torque
// (σ̇ = −G₁, the ground's reaction passes through the foot), so along the gait's path
// σ² − Φ(α) is conserved with dΦ/dα = −2 G₁ f (3.14): from the state (α, σ) the robot reaches
// the highest point of its path (the minimum of Φ ahead, the centre of mass over the foot) with
// σ_apex² = σ² − Φ(α) + min Φ ahead. The gait itself passes it with σ_iSS² + min Φ (Φ(α_iSS) = 0).
// A robot off the path (a trunk lean, a swing leg behind) has another gravity torque G₁ at the
// same α; the prediction carries the difference ΔG₁ to the apex: −2 ΔG₁ ∫ f dα from α to it.
#include <vector>

#include "gaitopt/gait/evaluation.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

class ApexEnergy {
 public:
  // Φ sampled on `samples` uniform intervals of the SS path's α range [α_iSS, α_fSS].
  ApexEnergy(const Model& model, const GaitMotion<double>& motion, int samples = 200);

  // σ_apex² [(kg·m²/s)²] reached from (α, σ) with the gravity torque G₁ = M g x_G [N·m] about
  // the stance foot, negative when the robot falls back before the apex; σ of the wrong sign
  // (the robot already turning back) counts as −σ². Past α_fSS: σ².
  double predicted(double alpha, double sigma, double gravity_torque) const;
  double gait() const { return gait_; }  // the gait's σ_apex²
  // σ_apex² of a single support started on the path at α_start (α_iSS or later: a late
  // touchdown) at rate_scale times the gait's rate there, with a gravity torque off the gait's by
  // gravity_torque_offset [N·m] all the way to the apex.
  double fromStart(double alpha_start, double rate_scale, double gravity_torque_offset) const;
  // The smallest such rate_scale that passes the apex with σ_apex² ≥ fraction × gait().
  double minStartRateScale(double alpha_start, double fraction) const;

 private:
  double alpha0_ = 0.0, dalpha_ = 0.0;  // α of sample 0 and the spacing (signed)
  // Φ, its minimum ahead, G₁ along the path, ∫ f dα from α_iSS, and that integral at the
  // minimum ahead.
  std::vector<double> phi_, phi_min_ahead_, torque_, f_integral_, f_integral_apex_;
  double sigma_start_ = 0.0, gait_start_ = 0.0, gait_ = 0.0;  // σ_iSS, σ_iSS², σ_apex²
  double interpolate(const std::vector<double>& v, double alpha) const;
  double changeToApex(double alpha, double gravity_torque_offset) const;
};

// The angular momentum about the stance foot σ = ∂T/∂α̇ = (A q̇)₁ of the pinned model at (q, q̇)
// (α absolute: the momentum conjugate to it is the whole robot's), and gravity's torque about
// the foot G₁ = M g x_G.
struct StanceMomentum {
  double sigma, gravity_torque;
};
StanceMomentum stanceMomentum(const Model& model, const Vec5& q, const Vec5& qd);

}  // namespace gaitopt
