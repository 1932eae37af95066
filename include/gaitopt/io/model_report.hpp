#pragma once
// The JSON document printed by `gaitopt model`: pinned and floating model terms at one state,
// and single-support inverse dynamics when an acceleration is given.
#include <optional>
#include <string>

#include "gaitopt/model/model.hpp"

namespace gaitopt {

std::string modelReportJson(const Model& model, const Vec5& q, const Vec5& qd,
                            const std::optional<Vec5>& qdd);

}  // namespace gaitopt
