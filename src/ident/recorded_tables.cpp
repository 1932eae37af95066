#include "gaitopt/ident/recorded_tables.hpp"

#include <algorithm>
#include <vector>

#include "gaitopt/ident/data_error.hpp"

namespace gaitopt {

namespace {

// Columns called `name` or named by a path whose last-but-one part is `name`
// (`/jointset/hip_r/hip_flexion_r/value`).
std::vector<std::size_t> matchingColumns(const std::vector<std::string>& columns,
                                         const std::string& name) {
  std::vector<std::size_t> exact, path;
  const std::string tail = "/" + name + "/value";
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (columns[c] == name) exact.push_back(c);
    const std::string& s = columns[c];
    if (s.size() > tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0)
      path.push_back(c);
  }
  return exact.empty() ? path : exact;
}

}  // namespace

bool OpenSimTable::hasColumn(const std::string& name) const {
  return matchingColumns(columns, name).size() == 1;
}

Eigen::VectorXd OpenSimTable::column(const std::string& name) const {
  const std::vector<std::size_t> found = matchingColumns(columns, name);
  if (found.empty()) throw DataError(file, name, 0, "column missing from the table");
  if (found.size() > 1)
    throw DataError(file, name, 0, "several columns end in /" + name + "/value: ambiguous");
  return values.col(static_cast<Eigen::Index>(found.front()));
}

Eigen::MatrixX3d TrcData::marker(const std::string& name) const {
  const auto it = std::find(markers.begin(), markers.end(), name);
  if (it == markers.end()) throw DataError(file, name, 0, "marker missing from the file");
  return positions.middleCols<3>(3 * (it - markers.begin()));
}

}  // namespace gaitopt
