#pragma once
// One walking step sampled at a fixed rate: SS rows at t = k/rate on [0, T_SS] and DS rows on
// [T_SS, T_SS + T_DS], each phase closed by a row at its exact end so phase integrals over the
// samples are exact up to the quadrature rule. Positions are in the frame of the stance foot
// (foot 1 at the origin).
#include <string>
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
};

// Requires evaluation.motion_computed.
std::vector<TrajectoryRow> sampleTrajectory(const GaitEvaluator& evaluator,
                                            const GaitEvaluation<double>& evaluation,
                                            double rate);

// One sample at time t from the start of `phase` (0 ≤ t ≤ T_SS or T_DS); its `t` is from SS
// start. Requires evaluation.motion_computed.
TrajectoryRow sampleTrajectoryAt(const GaitEvaluator& evaluator,
                                 const GaitEvaluation<double>& evaluation, Phase phase, double t);

// trajectory.csv: t, phase, alpha, delta1..4, alphad, delta1d..4d, alphadd, delta1dd..4dd,
// gamma1..4 (Γ*), R1x, R1z, R2x, R2z, x_swing, z_swing, x_com, z_com.
std::string trajectoryCsv(const std::vector<TrajectoryRow>& rows);

}  // namespace gaitopt
