#pragma once
// A defined starting step built from the robot's geometry: hip midway between the feet at DS
// start, slightly ahead at DS end, knees bent as in the thesis' DS gaits, trunk leaning 0.05
// rad forward, stance-tibia rate from the requested speed. It satisfies hierarchy levels 0–4
// on the shipped robots; the optimiser does the rest.
#include <optional>

#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

GaitParameters defaultInitialGuess(const Model& model, std::optional<double> speed);

}  // namespace gaitopt
