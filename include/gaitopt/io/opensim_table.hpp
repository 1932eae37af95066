#pragma once
// Strict reader of OpenSim storage files (.mot, .sto): a free-text header closed by a line
// `endheader` (with `key=value` lines such as nRows, nColumns, inDegrees), then a row of
// tab-separated column names starting with `time`, then one tab-separated numeric row per
// sample. Values are returned as written: `in_degrees` says whether the rotational columns are
// in degrees, but which columns are rotational is known only to the caller (an IK file mixes
// pelvis_tilt [deg] with pelvis_tx [m] under inDegrees=yes).
#include <string>

#include "gaitopt/ident/recorded_tables.hpp"

namespace gaitopt {

// Throws ConfigError naming the file, the column and the line for: no `endheader`; a missing
// or malformed inDegrees flag; a header nRows/nColumns that disagrees with the table
// (e.g. a truncated file); duplicate or empty column names; a first column other than `time`;
// a row with the wrong number of fields; a non-numeric or non-finite value; a time that does
// not increase strictly; fewer than 2 rows. Limits: see tab_text.hpp.
OpenSimTable readOpenSimTable(const std::string& path);

}  // namespace gaitopt
