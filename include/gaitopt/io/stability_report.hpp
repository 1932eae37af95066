#pragma once
// The files of a stability study (sim/stability_study.hpp): stability.json, jacobian.csv,
// zero_dynamics_map.csv and, for a gait with double support, ds_bounds.csv.
#include <Eigen/Core>
#include <string>

#include "gaitopt/sim/stability_study.hpp"

namespace gaitopt {

// stability.json of the study of the gait file `gait` made with `request`.
std::string stabilityJson(const StabilityStudy& study, const StabilityRequest& request,
                          const std::string& gait);

// The Poincaré Jacobian, one row per state component (α, δ1..δ4, then their rates).
std::string jacobianCsv(const Eigen::MatrixXd& jacobian);

// Per start α̇_iSS of the zero-dynamics map: the next α̇ and the steps to the cycle.
std::string zeroDynamicsMapCsv(const ZeroDynamicsStudy& study);

// Fig. 4.5: per α̇_fDS the zone's ends at α_iDS and a (4.28).
std::string dsBoundsCsv(const DsZoneStudy& study);

// Writes the study's files into the directory `dir` (created if missing).
void writeStabilityReport(const std::string& dir, const StabilityStudy& study,
                          const StabilityRequest& request, const std::string& gait);

}  // namespace gaitopt
