#pragma once
// trajectory.csv of a sampled walking step (gait/trajectory.hpp).
#include <string>
#include <vector>

#include "gaitopt/gait/trajectory.hpp"

namespace gaitopt {

// trajectory.csv: t, phase, alpha, delta1..4, alphad, delta1d..4d, alphadd, delta1dd..4dd,
// gamma1..4 (Γ*), R1x, R1z, R2x, R2z, x_swing, z_swing, x_com, z_com, then x/z of knee1, hip,
// knee2, head, omega1..4, gamma_max1..4, sigma, z_clearance, zd_potential (empty in DS).
std::string trajectoryCsv(const std::vector<TrajectoryRow>& rows);

}  // namespace gaitopt
