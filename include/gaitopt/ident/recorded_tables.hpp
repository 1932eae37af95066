#pragma once
// Recorded tables of a walking trial as the OpenSim tools write them, read by io/opensim_table.hpp
// (.mot, .sto) and io/trc_file.hpp (.trc markers).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace gaitopt {

// An OpenSim storage table. Values as written: `in_degrees` says whether the rotational columns
// are in degrees, but which columns are rotational is known only to the caller.
struct OpenSimTable {
  std::string file;
  std::vector<std::string> columns;  // columns[0] == "time"
  Eigen::MatrixXd values;            // rows × columns, column 0 the time [s]
  bool in_degrees = false;
  bool units_declared = true;        // false: no inDegrees line (in_degrees then false)
  int first_data_line = 0;           // 1-based line of the first data row (for messages)

  Eigen::Index rows() const { return values.rows(); }
  Eigen::VectorXd time() const { return values.col(0); }
  // The column called `name`, or the one whose path names it (`/jointset/hip_r/hip_flexion_r/value`
  // as OpenSim 4 writes coordinates); DataError (file, column) when there is none or several.
  Eigen::VectorXd column(const std::string& name) const;
  bool hasColumn(const std::string& name) const;
};

// Motion-capture markers.
struct TrcData {
  std::string file;
  double rate = 0.0;                 // DataRate [Hz]
  std::vector<std::string> markers;  // names, in file order
  Eigen::VectorXd time;              // [s]
  Eigen::MatrixXd positions;         // frames × 3·markers, [m] (converted from Units)

  // frames × 3 positions (lab X, Y, Z) of marker `name`; DataError (file, name) when absent.
  Eigen::MatrixX3d marker(const std::string& name) const;
};

}  // namespace gaitopt
