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

// Both header versions are read: `key=value` lines (version=1 .mot, version=3 .sto) and the old
// `datarows N` / `datacolumns N` lines. inDegrees is optional (units_declared says whether it
// was given; the IK reader requires it); nColumns is informative (OpenSim's RRA output declares
// more columns than it writes) and each row is checked against the name row.
// Throws ConfigError naming the file, the column and the line for: no `endheader`; a
// malformed inDegrees flag; a header nRows/datarows that disagrees with the table
// (e.g. a truncated file); duplicate or empty column names; a first column other than `time`;
// a row with the wrong number of fields; a non-numeric or non-finite value; a time that does
// not increase strictly; fewer than 2 rows. Limits: see tab_text.hpp.
OpenSimTable readOpenSimTable(const std::string& path);

}  // namespace gaitopt
