#pragma once
// Strict reader of OpenSim storage files (.mot, .sto): a free-text header closed by a line
// `endheader` (with `key=value` lines such as nRows, nColumns, inDegrees), then a row of
// tab-separated column names starting with `time`, then one tab-separated numeric row per
// sample. Values are returned as written: `in_degrees` says whether the rotational columns are
// in degrees, but which columns are rotational is known only to the caller (an IK file mixes
// pelvis_tilt [deg] with pelvis_tx [m] under inDegrees=yes).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace gaitopt {

struct OpenSimTable {
  std::string file;
  std::vector<std::string> columns;  // columns[0] == "time"
  Eigen::MatrixXd values;            // rows × columns, column 0 the time [s]
  bool in_degrees = false;
  int first_data_line = 0;           // 1-based line of the first data row (for messages)

  Eigen::Index rows() const { return values.rows(); }
  Eigen::VectorXd time() const { return values.col(0); }
  // The column called `name`; ConfigError (file, column) when there is none.
  Eigen::VectorXd column(const std::string& name) const;
  bool hasColumn(const std::string& name) const;
};

// Throws ConfigError naming the file, the column and the line for: no `endheader`; a missing
// or malformed inDegrees flag; a header nRows/nColumns that disagrees with the table
// (e.g. a truncated file); duplicate or empty column names; a first column other than `time`;
// a row with the wrong number of fields; a non-numeric or non-finite value; a time that does
// not increase strictly; fewer than 2 rows. Limits: see tab_text.hpp.
OpenSimTable readOpenSimTable(const std::string& path);

}  // namespace gaitopt
