#pragma once
// JSON of an impact result (the `gaitopt impact` document; reusable as a block of others).
#include "gaitopt/impact/impact_result.hpp"
#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {

// Writes the members model, mu, V2_minus, status, solutions, notes into the open object.
void writeImpactResultFields(JsonWriter& w, const ImpactResult& r);

}  // namespace gaitopt
