#pragma once
// Behaviour maps over the direction θ of the arriving foot velocity V2⁻ = (cos θ, sin θ) and
// the friction coefficient μ (§2.4.2, the region plots of Figs. 2.3–2.16).
#include <string>
#include <vector>

#include "gaitopt/impact/solve_impact.hpp"

namespace gaitopt {

// Least-norm pinned velocities q̇ (foot 1 at rest) giving foot 2 the velocity v2: the impact
// depends on q̇ only through V2⁻ (digest §1.5), so this is the canonical pre-impact state.
Vec5 pinnedVelocityForFoot2(const Model& model, const Vec5& q, const Vec2& v2);

// A closed θ-interval [rad] on which one algebraic behaviour is consistent at one μ.
struct ThetaInterval {
  ImpactBehaviour behaviour;
  double begin, end;
};

// Exact θ-intervals of every algebraic behaviour on [theta_min, theta_max]: each slack is
// a cos θ + b sin θ (linear and homogeneous in V2⁻), so the interval ends are the zeros of
// those sinusoids; between consecutive zeros the sign pattern is constant.
std::vector<ThetaInterval> algebraicThetaIntervals(const Model& model, const Vec5& q, double mu,
                                                   double theta_min, double theta_max);

struct ImpactMapRow {
  double theta, mu;                        // [rad], [-]
  std::vector<ImpactBehaviour> behaviours;  // every solution's behaviour
  ImpactStatus status;
};

// Samples: algebraic model from the exact intervals, differential model by solving at each
// sample. Ranges are inclusive with n points each (n = 1: the start value).
struct ImpactMapRequest {
  ImpactModelKind model = ImpactModelKind::Algebraic;
  double mu_min = 0.0, mu_max = 1.0;
  int mu_count = 11;
  double theta_min = -M_PI, theta_max = 0.0;
  int theta_count = 181;
  ImpactOptions options;  // tolerances; mu is overwritten per sample
};

std::vector<ImpactMapRow> impactMap(const Model& model, const Vec5& q, const ImpactMapRequest& r);

// "lift/stick" style label of a behaviour.
std::string behaviourLabel(ImpactBehaviour b);

}  // namespace gaitopt
