#pragma once
// The interpolating cubic spline of Forsythe, Malcolm & Moler (Computer Methods for
// Mathematical Computations, 1977, §4.4): at each end the spline's third derivative equals
// that of the cubic through the four nearest knots (a straight line for two knots, a parabola
// end condition for three). This is the spline OpenSim evaluates for a SimmSpline (e.g. the
// knee translation of the gait models), so a value computed here is the model's value.
// Beyond the knots the spline is continued by its end tangent, as OpenSim does.
#include <vector>

namespace gaitopt {

// Value at `x` of the spline through (xs[i], ys[i]); xs strictly increasing, at least 2 knots
// (callers check).
double fmmSplineValue(const std::vector<double>& xs, const std::vector<double>& ys, double x);

}  // namespace gaitopt
