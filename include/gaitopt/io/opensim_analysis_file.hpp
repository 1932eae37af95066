#pragma once
// The point-foot analysis of an imported trial (ident/opensim_analysis.hpp) as JSON, the
// `--report` of `gaitopt import-opensim`.
#include <string>

#include "gaitopt/ident/opensim_analysis.hpp"

namespace gaitopt {

std::string opensimAnalysisJson(const OpenSimAnalysis& analysis);

}  // namespace gaitopt
