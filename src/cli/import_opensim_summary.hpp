#pragma once
// What `gaitopt import-opensim` prints, and the import sanity checks it applies before the
// data go to `diagnose`.
#include <optional>

#include "gaitopt/ident/opensim_analysis.hpp"
#include "gaitopt/ident/opensim_import.hpp"

namespace gaitopt::cli {

// Lowest hip/knee correlation with OpenSim's inverse dynamics accepted without a warning, and
// the stance heel speed after belt removal above which the import warns [m/s].
constexpr double kMinMomentCorrelation = 0.9;
constexpr double kMaxStanceHeelSpeed = 0.1;

// Conventions, dropped samples, belt, gait events, samples and steps.
void printSummary(const ImportedTrial& trial);

// The point-foot analysis, the force balance, and the sanity checks: a hip or knee moment that
// correlates negatively with OpenSim's is a ConfigError at --id (a sign convention is wrong);
// below kMinMomentCorrelation, or a stance heel speed above kMaxStanceHeelSpeed, a WARNING on
// stderr.
void printAnalysisAndCheck(const ImportedTrial& trial, const OpenSimAnalysis& a,
                           const std::string& id_file);

}  // namespace gaitopt::cli
