#include "gaitopt/io/trajectory_file.hpp"

#include <sstream>

#include "gaitopt/io/csv_table.hpp"

namespace gaitopt {

std::string trajectoryCsv(const std::vector<TrajectoryRow>& rows) {
  std::ostringstream out;
  out << csvHeader({"t", "phase", "alpha", "delta1", "delta2", "delta3", "delta4", "alphad",
                    "delta1d", "delta2d", "delta3d", "delta4d", "alphadd", "delta1dd", "delta2dd",
                    "delta3dd", "delta4dd", "gamma1", "gamma2", "gamma3", "gamma4", "R1x", "R1z",
                    "R2x", "R2z", "x_swing", "z_swing", "x_com", "z_com", "x_knee1", "z_knee1",
                    "x_hip", "z_hip", "x_knee2", "z_knee2", "x_head", "z_head", "omega1", "omega2",
                    "omega3", "omega4", "gamma_max1", "gamma_max2", "gamma_max3", "gamma_max4",
                    "sigma", "z_clearance", "zd_potential"});
  for (const TrajectoryRow& r : rows) {
    CsvRow row;
    row.number(r.t).text(r.phase == Phase::SingleSupport ? "SS" : "DS");
    row.numbers(r.q).numbers(r.qd).numbers(r.qdd).numbers(r.gamma_star);
    row.numbers(r.R1).numbers(r.R2).numbers(r.foot2).numbers(r.com);
    for (const Vec2* p : {&r.knee1, &r.hip, &r.knee2, &r.head}) row.numbers(*p);
    row.numbers(r.omega).numbers(r.gamma_max).number(r.sigma).number(r.clearance);
    out << row.number(r.zd_potential).line();
  }
  return out.str();
}

}  // namespace gaitopt
