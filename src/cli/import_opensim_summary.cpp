#include "import_opensim_summary.hpp"

#include <iostream>

#include "cli_common.hpp"
#include "gaitopt/io/config_error.hpp"

namespace gaitopt::cli {

void printSummary(const ImportedTrial& trial) {
  for (const std::string& s : trial.conventions.statements) std::cout << s << "\n";
  for (const std::string& n : trial.notes) std::cout << "note: " << n << "\n";
  std::cout << "belt speed " << shortNumber(trial.belt_speed, "%.4f") << " m/s ("
            << trial.belt_source << "), trunk line from " << trial.trunk_source << "\n";
  if (trial.belt_source == "IK ankle") {
    std::cout << "  note: the IK ankle creeps forward in stance (about 0.1 m/s on the shipped trial);"
                 " give --trc or --belt-speed for a better estimate\n";
  }
  for (const GaitEvent& e : trial.events) {
    std::cout << "  " << shortNumber(e.time, "%.4f") << " s  " << sideName(e.side) << ' '
              << (e.heel_strike ? "heel strike" : "toe off") << "\n";
  }
  std::cout << trial.t.size() << " samples, " << trial.step.back() + 1 << " steps\n";
}

void printAnalysisAndCheck(const ImportedTrial& trial, const OpenSimAnalysis& a,
                           const std::string& id_file) {
  for (const JointComparison& j : a.joints) {
    std::cout << j.joint << ": RMS difference to OpenSim " << shortNumber(j.rms, "%.2f")
              << " N m (reference RMS " << shortNumber(j.reference_rms, "%.2f")
              << "), correlation " << shortNumber(j.correlation, "%.3f") << "\n";
  }
  std::cout << "whole-body force balance residual RMS x " << shortNumber(a.force_residual_rms_x, "%.1f")
            << " N, z " << shortNumber(a.force_residual_rms_z, "%.1f") << " N\n";
  if (trial.stance_heel_speed)
    std::cout << "stance heel speed after belt removal: median " << shortNumber(*trial.stance_heel_speed, "%.3f")
              << " m/s\n";
  std::cout << "single-support alpha-row residual RMS " << shortNumber(a.alpha_residual_rms, "%.2f")
            << " N m, measured CoP moment RMS " << shortNumber(a.cop_moment_rms, "%.2f")
            << " N m, correlation " << shortNumber(a.alpha_cop_correlation, "%.3f")
            << "; left unexplained with the measured CoP " << shortNumber(a.alpha_minus_cop_rms, "%.2f")
            << " N m, with a rocker foot " << shortNumber(a.alpha_minus_rocker_rms, "%.2f") << " N m\n";
  std::cout << "rocker radius " << shortNumber(a.rocker.radius_all, "%.3f") << " m = "
            << shortNumber(a.rocker.radius_all / a.rocker.leg_length, "%.3f")
            << " x leg length (literature ~0.3); held-out CoP RMS point foot "
            << shortNumber(a.rocker.holdout_rms_point, "%.4f") << " m, rocker "
            << shortNumber(a.rocker.holdout_rms_rocker, "%.4f") << " m\n";
  for (const JointComparison& j : a.joints) {
    if (j.correlation < 0.0)
      throw ConfigError(id_file, j.joint, 0,
                        "the imported " + j.joint + " moment correlates negatively (" +
                            shortNumber(j.correlation, "%.3f") +
                            ") with OpenSim's: a sign convention is wrong (knee_flexion, plates?)");
    if (j.correlation < kMinMomentCorrelation)
      std::cerr << "WARNING: " << j.joint << " moment correlates " << shortNumber(j.correlation, "%.3f")
                << " with OpenSim's, below " << kMinMomentCorrelation
                << ": check the conventions and the robot file before diagnose\n";
  }
  if (trial.stance_heel_speed && *trial.stance_heel_speed > kMaxStanceHeelSpeed)
    std::cerr << "WARNING: the stance heel moves at " << shortNumber(*trial.stance_heel_speed, "%.3f")
              << " m/s after belt removal (above " << kMaxStanceHeelSpeed
              << "): belt speed or plate sides wrong?\n";
}

}  // namespace gaitopt::cli
