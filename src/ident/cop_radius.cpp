#include "gaitopt/ident/cop_radius.hpp"

#include <cmath>
#include <stdexcept>

#include "gaitopt/ident/diagnosis_fit.hpp"

namespace gaitopt {

CopRadius copRadius(const PreparedData& p, const RobotParams& robot, const ModelOptions& mo,
                    const std::vector<char>& rows) {
  if (!p.data.has_cop) throw std::invalid_argument("copRadius: the data have no centres of pressure");
  // The cop1x residual is affine in the radius: two evaluations give it exactly.
  RobotParams unit = robot;
  unit.foot_radius += 1.0;
  const ResidualMatrix r0 = residuals(p, robot, mo, rows), r1 = residuals(p, unit, mo, rows);
  std::vector<diagnosis::Entry> entries;
  for (std::size_t s = 0; s < p.segments.size(); ++s)
    for (std::size_t i = p.segments[s].begin; i < p.segments[s].end; ++i)
      if (std::isfinite(r0(i, kCopX))) entries.push_back({i, kCopX, static_cast<int>(s)});
  CopRadius c;
  c.samples = static_cast<int>(entries.size());
  c.radius = robot.foot_radius;
  if (entries.size() < 2) return c;
  const Eigen::VectorXd base = diagnosis::entryValues(entries, r0);
  const Eigen::VectorXd column = diagnosis::entryValues(entries, r1) - base;
  const double cc = column.squaredNorm();
  if (cc <= 0.0) return c;
  const double step = -column.dot(base) / cc;
  const Eigen::VectorXd left = base + column * step;
  const double s2 = left.squaredNorm() / static_cast<double>(entries.size() - 1);
  c.radius += step;
  c.stderr_ = std::sqrt(diagnosis::inflation(entries, left) * s2 / cc);
  return c;
}

}  // namespace gaitopt
