#pragma once
// Strict reader of motion-capture marker files in the .trc text format (as written by
// Cortex/OpenSim): line 1 `PathFileType ...`, line 2 the names and line 3 the values of
// DataRate, CameraRate, NumFrames, NumMarkers, Units, ...; line 4 `Frame#`, `Time` and the
// marker names (each followed by two empty fields); line 5 the X/Y/Z labels; then one row per
// frame: frame number, time, X Y Z of every marker. Tab-separated.
#include <string>

#include "gaitopt/ident/recorded_tables.hpp"

namespace gaitopt {

// Throws ConfigError naming the file, the column and the line for: a missing or malformed
// header (wrong first word, header names/values that do not pair up once the empty fields of
// the values line are dropped, NumMarkers or
// NumFrames not matching the table, Units other than mm/m), a row with the wrong number of
// fields, an empty (occluded) or non-numeric value, a non-increasing time, a frame count
// different from NumFrames (truncated file). Gaps are not filled: a marker file with
// occlusions must be gap-filled first. Limits: see tab_text.hpp. The declared Units are checked
// against the data: a coordinate beyond kMaxMarkerDistance (millimetres declared as `m`) or
// every coordinate within kMinMarkerSpread of the origin (metres declared as `mm`) is refused.
TrcData readTrcFile(const std::string& path);

// A gait laboratory's extent and the least extent of a walking subject's markers [m].
constexpr double kMaxMarkerDistance = 50.0;
constexpr double kMinMarkerSpread = 0.05;

}  // namespace gaitopt
