#pragma once
// Landing with an impact (beyond the thesis): the swing foot reaches the ground with
// the velocity q*(α_fSS) α̇_fSS of the SS path, whose end slopes δ3*, δ4* are now free
// parameters (the thesis fixes them by a zero foot velocity (3.20)); the algebraic impact
// (2.1)/(2.13) runs at touchdown with the behaviour the gait family requires:
//   - ImpactSingleSupport: foot 1 lifts and foot 2 sticks, the new stance leg starts its SS
//     at once (the gait of Chevallereau & Aoustin and of the HZD walkers);
//   - ImpactDoubleSupport: both feet stick, a double support follows.
// The impact is linear in the pre-impact velocity given the configuration, so it is computed
// once per unit rate α̇⁻ = −1 rad/s and scaled; the post-impact velocity, relabelled by the leg
// exchange (3.22)–(3.23), gives the rate ratio λ = α̇⁺/α̇⁻ and the slopes ∂q/∂α that start the
// next phase (cyclicity through the impact).
#include <string>

#include "gaitopt/gait/leg_geometry.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/impact/algebraic_impact_equations.hpp"
#include "gaitopt/model/dynamics_floating.hpp"

namespace gaitopt {

// The parameters the evaluator reads. Without DS the SS starts at the post-impact configuration
// (α_iDS, δ1_iDS, θ3_iDS), which thus also stands for (α_fDS, δ1_fDS, θ3_fDS), and T_DS = 0;
// the other unused entries (Parameterisation::isUsed) are not read.
template <class S>
GaitVector<S> landingParameters(const GaitVector<S>& p, const Parameterisation& par) {
  GaitVector<S> pe = p;
  if (par.hasDoubleSupport()) return pe;
  pe(kAlphaFDS) = p(kAlphaIDS);
  pe(kDelta1FDS) = p(kDelta1IDS);
  pe(kTheta3FDS) = p(kTheta3IDS);
  pe(kTDS) = S(0.0);
  return pe;
}

// The behaviour a landing requires (the old stance foot is foot 1, the landing foot foot 2).
ImpactBehaviour landingBehaviour(Landing landing);
int landingImpactSlackCount(Landing landing);

template <class S> struct LandingImpact {
  Vector5<S> slopes_before = Vector5<S>::Zero();  // ∂q/∂α of the SS path at touchdown
  Vector7<S> X = Vector7<S>::Zero();              // floating configuration at touchdown
  Vector7<S> Xd_minus = Vector7<S>::Zero();       // per unit rate α̇⁻ = −1 rad/s
  Vector2<S> v2_minus = Vector2<S>::Zero();       // arriving foot velocity, per unit rate
  ImpactOutcome<S> unit;                          // the impact, per unit rate
  Vector5<S> slopes_after = Vector5<S>::Zero();   // ∂q/∂α after it, new stance labelling
  S rate_ratio = S(0.0);                          // λ = α̇⁺/α̇⁻ (new stance α over old)
};

// The impact at the touchdown configuration q (foot 1 at the origin, foot 2 on the ground)
// for the SS-end slopes `slopes` (∂q/∂α, first entry 1).
template <class S>
LandingImpact<S> landingImpact(const Model& m, const Vector5<S>& q, const Vector5<S>& slopes,
                               Landing landing, double mu) {
  LandingImpact<S> r;
  r.slopes_before = slopes;
  floatingStateFromPinned(m, q, Vector5<S>(-slopes), r.X, r.Xd_minus);
  const ImpactSystem<S> sys = impactSystem(m, r.X, r.Xd_minus);
  r.v2_minus = sys.V_minus.template tail<2>();
  r.unit = algebraicImpact(sys, landingBehaviour(landing), mu);
  const Vector5<S> qd_new = exchangeLegVelocities(Vector5<S>(r.unit.Xd_plus.template head<5>()));
  r.rate_ratio = -qd_new(0);
  r.slopes_after = qd_new / qd_new(0);
  return r;
}

// The behaviour's inequalities as g ≤ 0 entries with a margin, impulse slacks divided by the
// total mass so that every entry is a velocity per unit rate [m/s per rad/s].
template <class S>
void landingConsistency(const Model& m, const LandingImpact<S>& li, Landing landing,
                        std::vector<S>& g) {
  constexpr double kMargin = 1e-3;
  const std::vector<SlackInfo> info = impactSlacks(landingBehaviour(landing));
  g.clear();
  for (std::size_t k = 0; k < info.size(); ++k) {
    const S& slack = li.unit.slacks(static_cast<Eigen::Index>(k));
    g.push_back(kMargin - (info[k].kind == SlackKind::Impulse ? S(slack / m.total_mass) : slack));
  }
}

// The impact at the actual pre-impact rate α̇⁻ (< 0): velocities and impulses scale with
// −α̇⁻, the energy loss with α̇⁻².
struct LandingReport {
  ImpactBehaviour behaviour;
  Vector7<double> X, Xd_minus, Xd_plus;
  Vector2<double> v2_minus, impulse1, impulse2;
  double energy_loss;
  double alphadot_minus, alphadot_plus;  // old stance, new stance labelling
};
LandingReport landingReport(const LandingImpact<double>& li, Landing landing,
                            double alphadot_minus);

// Both impact solvers (impact/solve_impact.hpp) at the reported touchdown. The landing
// requires the algebraic model's status "unique" with its own behaviour; the differential
// model (Keller's) is reported beside it, with the largest difference of its post-impact
// velocities from the gait's [same units as Xd].
struct LandingSolutions {
  std::string status;  // unique | indeterminate | inconsistent
  int count = 0;
  bool required_found = false;
  std::string differential_status;
  int differential_count = 0;
  double differential_difference = 0.0;
};
LandingSolutions landingSolutions(const Model& model, const LandingReport& report, double mu);

const char* afterImpactName(Landing landing);  // single_support | double_support

}  // namespace gaitopt
