#pragma once
// The CSV file of measured walking data (ident/measured_data.hpp): one row per sample, a
// header row, SI units, radians.
// Required columns t, alpha, delta1..delta4, phase (SS/DS), stance (left/right: the physical
// leg that is leg 1 of the thesis convention at that sample), step (integer, increasing);
// optional gamma1..gamma4 (measured joint-side motor torques Γ*, motor order) and
// R1x, R1z, R2x, R2z (ground reactions, gravity frame), and with them cop1x, cop2x (world x of
// the centre of pressure of leg 1 / leg 2 [m], gravity frame; a leg without load has its point
// foot's x), each group complete or absent. Columns
// may come in any order; time may have gaps between steps.
#include <string>

#include "gaitopt/ident/measured_data.hpp"
#include "gaitopt/model/robot_params.hpp"

namespace gaitopt {

// Minimum samples per step and steps per file accepted by readMeasuredCsv.
constexpr int kMinSamplesPerStep = 20;
constexpr int kMinSteps = 3;

// Plausibility limits (docs/reliability.md): more samples than kMaxMeasuredRows would cost
// `diagnose` over about 1 GB; a joint angle beyond two turns is not radians of a walking robot
// (degrees, a broken encoder); a time gap inside a step over kMaxGapInSamples median sample
// intervals is a recording fault (gaps belong between steps); a torque beyond
// kMaxTorqueEnvelopeMultiple times the robot's largest envelope torque is not a motor torque.
constexpr std::size_t kMaxMeasuredRows = 100000;
constexpr double kMaxMeasuredAngle = 12.566370614359172;  // 4 pi rad
constexpr double kMaxGapInSamples = 10.0;
constexpr double kMaxTorqueEnvelopeMultiple = 10.0;

// Throws ConfigError naming the file, the CSV line, the row and column and the problem: missing
// or unknown column, incomplete optional group, NaN/inf or non-numeric value, non-increasing
// time, unknown phase/stance label, non-integer or decreasing step, a step repeated after
// another, a step with fewer than kMinSamplesPerStep samples, fewer than kMinSteps steps, no
// torque and no reaction columns at all, more than kMaxMeasuredRows rows, an angle beyond
// kMaxMeasuredAngle, a time gap inside a step beyond kMaxGapInSamples sample intervals.
MeasuredData readMeasuredCsv(const std::string& path);

// Throws ConfigError naming `path`, the column and the sample when a measured torque exceeds
// kMaxTorqueEnvelopeMultiple times the largest torque of `robot`'s envelope.
void requirePlausibleTorques(const MeasuredData& data, const RobotParams& robot,
                             const std::string& path);

// The CSV text (header then rows, full precision); readMeasuredCsv reads it back identically.
std::string measuredCsv(const MeasuredData& data);

}  // namespace gaitopt
