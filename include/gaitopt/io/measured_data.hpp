#pragma once
// The CSV file of measured walking data (ident/measured_data.hpp): one row per sample, a
// header row, SI units, radians.
// Required columns t, alpha, delta1..delta4, phase (SS/DS), stance (left/right: the physical
// leg that is leg 1 of the thesis convention at that sample), step (integer, increasing);
// optional gamma1..gamma4 (measured joint-side motor torques Γ*, motor order) and
// R1x, R1z, R2x, R2z (ground reactions, gravity frame), each group complete or absent. Columns
// may come in any order; time may have gaps between steps.
#include <string>

#include "gaitopt/ident/measured_data.hpp"

namespace gaitopt {

// Minimum samples per step and steps per file accepted by readMeasuredCsv.
constexpr int kMinSamplesPerStep = 20;
constexpr int kMinSteps = 3;

// Throws ConfigError naming the file, the CSV line, the row and column and the problem: missing
// or unknown column, incomplete optional group, NaN/inf or non-numeric value, non-increasing
// time, unknown phase/stance label, non-integer or decreasing step, a step repeated after
// another, a step with fewer than kMinSamplesPerStep samples, fewer than kMinSteps steps, and no
// torque and no reaction columns at all.
MeasuredData readMeasuredCsv(const std::string& path);

// The CSV text (header then rows, full precision); readMeasuredCsv reads it back identically.
std::string measuredCsv(const MeasuredData& data);

}  // namespace gaitopt
