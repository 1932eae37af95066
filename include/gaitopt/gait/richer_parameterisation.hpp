#pragma once
// Writes a step of one parameterisation in a richer one without changing the motion: the extra
// interior configurations are sampled from the coarse polynomials, and the finer interpolant
// through points of a polynomial of lower degree is that polynomial. Used to warm-start a
// richer optimisation from the thesis' optimum, which it can then only improve.
#include "gaitopt/gait/evaluator.hpp"

namespace gaitopt {

// Throws std::invalid_argument when levels 0–1 fail at p (the polynomials do not exist) or
// when `fine` has fewer points than the coarse evaluator's parameterisation.
GaitParameters toRicherParameterisation(const GaitEvaluator& coarse, const GaitParameters& p,
                                const Parameterisation& fine);

}  // namespace gaitopt
