#pragma once
// The files of a closed-loop walk (sim/hybrid_walk.hpp) other than its trajectory:
// summary.json, steps.csv and tracking.csv.
#include <string>

#include "gaitopt/sim/hybrid_walk.hpp"

namespace gaitopt {

// What was simulated, as the summary reports it.
struct SimulationRun {
  std::string gait;          // gait file
  std::string plant;         // robot file of the simulated robot; empty: the gait's robot
  std::string impact_model;  // the touchdown model, resolved (sim/impact_touchdown.hpp)
  WalkRequest request;
  double cycle_alphad_start = 0.0;  // the gait's α̇_iSS
};

std::string simulationSummaryJson(const WalkResult& walk, const SimulationRun& run);

// One row per step: its events, energies, impact and saturation.
std::string walkStepsCsv(const WalkResult& walk);

// One row per sample: output errors, normal reactions and friction-cone margins at `mu`.
std::string walkTrackingCsv(const WalkResult& walk, double mu);

}  // namespace gaitopt
