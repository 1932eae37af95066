#include "gaitopt/control/apex_energy.hpp"

#include <algorithm>
#include <cmath>

#include "gaitopt/gait/zero_dynamics.hpp"
#include "gaitopt/model/chain_kinematics.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"

namespace gaitopt {

StanceMomentum stanceMomentum(const Model& model, const Vec5& q, const Vec5& qd) {
  const ChainState<double> st = chainState(model, q, qd);
  return {inertiaTimes(model, chainInertiaTheta(model.pinned, model.inertia, st), qd)(0),
          model.gravity * chainPoint(model.pinned.b, st)(0)};
}

// Φ by the trapezoidal rule on the uniform samples (f unsaturated: the controller's model
// along the gait, f > 0 on every defined gait (3.45)).
ApexEnergy::ApexEnergy(const Model& model, const GaitMotion<double>& mo, int samples) {
  alpha0_ = mo.q_iSS(0);
  dalpha_ = (mo.alpha_fSS - alpha0_) / samples;
  phi_.assign(samples + 1, 0.0);
  torque_.assign(samples + 1, 0.0);
  f_integral_.assign(samples + 1, 0.0);
  double rate = 0.0, f = 0.0;
  for (int k = 0; k <= samples; ++k) {
    const SsPathPoint<double> pt = ssPathPoint(model, mo, alpha0_ + k * dalpha_);
    const double r = phiRate(pt, 0.0), fk = saturatedF(pt.tau_a(0), 0.0);
    torque_[k] = pt.G(0);
    if (k == 0) {
      sigma_start_ = fk * mo.alphadot_iSS;  // σ = f α̇ (3.14)
    } else {
      phi_[k] = phi_[k - 1] + 0.5 * (rate + r) * dalpha_;
      f_integral_[k] = f_integral_[k - 1] + 0.5 * (f + fk) * dalpha_;
    }
    rate = r;
    f = fk;
  }
  phi_min_ahead_ = phi_;
  f_integral_apex_ = f_integral_;
  for (int k = samples - 1; k >= 0; --k) {
    if (phi_min_ahead_[k + 1] < phi_[k]) {
      phi_min_ahead_[k] = phi_min_ahead_[k + 1];
      f_integral_apex_[k] = f_integral_apex_[k + 1];
    }
  }
  gait_start_ = sigma_start_ * sigma_start_;
  gait_ = gait_start_ + phi_min_ahead_[0];
}

double ApexEnergy::interpolate(const std::vector<double>& v, double alpha) const {
  const double u = std::clamp((alpha - alpha0_) / dalpha_, 0.0, double(v.size() - 1));
  const std::size_t k = std::min(std::size_t(u), v.size() - 2);
  return v[k] + (u - k) * (v[k + 1] - v[k]);
}

// σ_apex² − σ²(α): min Φ ahead − Φ(α), and the off-path torque's work −2 ΔG₁ ∫ f dα to the apex.
double ApexEnergy::changeToApex(double alpha, double gravity_torque_offset) const {
  const double f_to_apex = interpolate(f_integral_apex_, alpha) - interpolate(f_integral_, alpha);
  return interpolate(phi_min_ahead_, alpha) - interpolate(phi_, alpha) -
         2.0 * gravity_torque_offset * f_to_apex;
}

double ApexEnergy::predicted(double alpha, double sigma, double gravity_torque) const {
  const double kinetic = sigma * sigma_start_ >= 0.0 ? sigma * sigma : -sigma * sigma;
  return kinetic + changeToApex(alpha, gravity_torque - interpolate(torque_, alpha));
}

// On the path the gait's σ² at α is σ_iSS² + Φ(α) (3.14).
double ApexEnergy::fromStart(double alpha, double rate_scale, double gravity_torque_offset) const {
  const double sigma2 = std::max(0.0, gait_start_ + interpolate(phi_, alpha));
  return rate_scale * rate_scale * sigma2 + changeToApex(alpha, gravity_torque_offset);
}

double ApexEnergy::minStartRateScale(double alpha, double fraction) const {
  const double sigma2 = gait_start_ + interpolate(phi_, alpha);
  const double needed = fraction * gait_ - changeToApex(alpha, 0.0);
  return sigma2 > 0.0 ? std::sqrt(std::max(0.0, needed) / sigma2) : 1.0;
}

}  // namespace gaitopt
