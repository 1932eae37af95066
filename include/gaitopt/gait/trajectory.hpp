#pragma once
// One walking step sampled at a fixed rate: SS rows at t = k/rate on [0, T_SS] and DS rows on
// [T_SS, T_SS + T_DS], each phase closed by a row at its exact end so phase integrals over the
// samples are exact up to the quadrature rule. Positions are in the frame of the stance foot
// (foot 1 at the origin).
#include <optional>
#include <vector>

#include "gaitopt/gait/evaluator.hpp"

namespace gaitopt {

enum class Phase { SingleSupport, DoubleSupport };

struct TrajectoryRow {
  double t;
  Phase phase;
  Vec5 q, qd, qdd;
  Vec4 gamma_star;
  Vec2 R1, R2;
  Vec2 foot2;  // swing foot in SS, rear foot in DS
  Vec2 com;
  // Drawing and plotting aids (columns appended after the original ones): joint points, the
  // joint speeds with their envelope torques, the angular momentum about foot 1 and, in SS,
  // the zero-dynamics potential.
  Vec2 knee1, hip, knee2, head;
  Vec4 omega, gamma_max;     // ω = D_Γᵀ q̇ and Γmax(ω) (3.47) as constrained by the options
  double sigma = 0.0;        // A[0,:] q̇, angular momentum about foot 1 [kg·m²/s]
  double clearance = 0.0;    // clearance bound z_max (1 − (x_swing/d)²) of (3.49) [m]
  std::optional<double> zd_potential;  // SS only: −Φ(α)/2, so σ²/2 + it is constant (3.14)
};

// A row's time, phase and motion (q, q̇, q̈, Γ*, R1, R2) from any sample that has those
// members (the evaluator's phase samples, the closed loop's walk samples).
template <class Sample>
TrajectoryRow motionRow(double t, Phase phase, const Sample& s) {
  TrajectoryRow r{};
  r.t = t;
  r.phase = phase;
  r.q = s.q;
  r.qd = s.qd;
  r.qdd = s.qdd;
  r.gamma_star = s.gamma_star;
  r.R1 = s.R1;
  r.R2 = s.R2;
  return r;
}

// Requires evaluation.motion_computed.
std::vector<TrajectoryRow> sampleTrajectory(const GaitEvaluator& evaluator,
                                            const GaitEvaluation<double>& evaluation,
                                            double rate);

// One sample at time t from the start of `phase` (0 ≤ t ≤ T_SS or T_DS); its `t` is from SS
// start. Requires evaluation.motion_computed.
TrajectoryRow sampleTrajectoryAt(const GaitEvaluator& evaluator,
                                 const GaitEvaluation<double>& evaluation, Phase phase, double t);

}  // namespace gaitopt
