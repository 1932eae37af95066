#pragma once
// The dimensionless cost of transport of a step: its electrical energy per metre C_E (3.32)
// divided by the robot's weight, the figure walking robots and animals are compared by.
#include "gaitopt/model/model.hpp"

namespace gaitopt {

inline double costOfTransport(const Model& model, double C_E) {
  return C_E / (model.total_mass * model.gravity);
}

}  // namespace gaitopt
