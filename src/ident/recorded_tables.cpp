#include "gaitopt/ident/recorded_tables.hpp"

#include <algorithm>

#include "gaitopt/ident/data_error.hpp"

namespace gaitopt {

bool OpenSimTable::hasColumn(const std::string& name) const {
  return std::find(columns.begin(), columns.end(), name) != columns.end();
}

Eigen::VectorXd OpenSimTable::column(const std::string& name) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  if (it == columns.end()) throw DataError(file, name, 0, "column missing from the table");
  return values.col(it - columns.begin());
}

Eigen::MatrixX3d TrcData::marker(const std::string& name) const {
  const auto it = std::find(markers.begin(), markers.end(), name);
  if (it == markers.end()) throw DataError(file, name, 0, "marker missing from the file");
  return positions.middleCols<3>(3 * (it - markers.begin()));
}

}  // namespace gaitopt
