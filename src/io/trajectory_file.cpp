#include "gaitopt/io/trajectory_file.hpp"

#include <sstream>

#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {

std::string trajectoryCsv(const std::vector<TrajectoryRow>& rows) {
  std::ostringstream out;
  out << "t,phase,alpha,delta1,delta2,delta3,delta4,alphad,delta1d,delta2d,delta3d,delta4d,"
         "alphadd,delta1dd,delta2dd,delta3dd,delta4dd,gamma1,gamma2,gamma3,gamma4,"
         "R1x,R1z,R2x,R2z,x_swing,z_swing,x_com,z_com,x_knee1,z_knee1,x_hip,z_hip,x_knee2,"
         "z_knee2,x_head,z_head,omega1,omega2,omega3,omega4,gamma_max1,gamma_max2,gamma_max3,"
         "gamma_max4,sigma,z_clearance,zd_potential\n";
  const auto put = [&out](const auto& v) {
    for (Eigen::Index i = 0; i < v.size(); ++i) out << ',' << formatDouble(v(i));
  };
  for (const TrajectoryRow& r : rows) {
    out << formatDouble(r.t) << ',' << (r.phase == Phase::SingleSupport ? "SS" : "DS");
    put(r.q);
    put(r.qd);
    put(r.qdd);
    put(r.gamma_star);
    put(r.R1);
    put(r.R2);
    put(r.foot2);
    put(r.com);
    for (const Vec2* p : {&r.knee1, &r.hip, &r.knee2, &r.head}) put(*p);
    put(r.omega);
    put(r.gamma_max);
    out << ',' << formatDouble(r.sigma) << ',' << formatDouble(r.clearance) << ',';
    if (r.zd_potential) out << formatDouble(*r.zd_potential);
    out << '\n';
  }
  return out.str();
}

}  // namespace gaitopt
