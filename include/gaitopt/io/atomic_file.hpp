#pragma once
// Outputs are written to a temporary sibling and renamed into place, so a failed run never
// leaves a half-written file behind.
#include <string>

namespace gaitopt {

void writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace gaitopt
