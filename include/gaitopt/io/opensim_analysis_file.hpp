#pragma once
// The point-foot analysis of an imported trial (ident/opensim_analysis.hpp) as JSON, the
// report.json of `gaitopt import-opensim --result`.
#include <string>

#include "gaitopt/ident/opensim_analysis.hpp"

namespace gaitopt {

// With the trial's conventions (as decided), notes, belt speed and stance heel speed.
std::string opensimAnalysisJson(const OpenSimAnalysis& analysis, const ImportedTrial& trial);

}  // namespace gaitopt
