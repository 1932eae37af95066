#include "gaitopt/gait/trajectory.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "gaitopt/gait/evaluator_impl.hpp"
#include "gaitopt/io/json_writer.hpp"

namespace gaitopt {
namespace {

TrajectoryRow toRow(double t, Phase phase, const detail::PhaseSample<double>& s) {
  return {t, phase, s.q, s.qd, s.qdd, s.gamma_star, s.R1, s.R2, s.foot2, s.com};
}

// s ∈ [−1, 1] with t(s) = t on the SS grid: t(s) is increasing as s goes from +1 to −1.
// Newton on the spectral interpolant, safeguarded by bisection.
double ssCoordinateAt(const ChebyshevGrid& grid, const Eigen::VectorXd& times, double t) {
  double hi = 1.0, lo = -1.0;  // t(hi) ≤ t ≤ t(lo)
  double s = 1.0 - 2.0 * t / times(times.size() - 1);
  for (int it = 0; it < 100; ++it) {
    const auto [value, slope] = grid.interpolateWithDerivative(times, s);
    const double r = value - t;
    if (std::abs(r) < 1e-14 * (1.0 + std::abs(t))) break;
    (r < 0.0 ? hi : lo) = s;
    double next = s - r / slope;
    if (!(next < hi && next > lo)) next = 0.5 * (hi + lo);
    s = next;
  }
  return s;
}

std::vector<double> phaseTimes(double duration, double rate) {
  std::vector<double> ts;
  for (int k = 0; k / rate < duration - 1e-12; ++k) ts.push_back(k / rate);
  ts.push_back(duration);
  return ts;
}

}  // namespace

std::vector<TrajectoryRow> sampleTrajectory(const GaitEvaluator& ev,
                                            const GaitEvaluation<double>& e, double rate) {
  if (!e.motion_computed) throw std::logic_error("sampleTrajectory: the step motion is undefined");
  std::vector<TrajectoryRow> rows;
  for (double t : phaseTimes(e.motion.T_SS, rate))
    rows.push_back(sampleTrajectoryAt(ev, e, Phase::SingleSupport, t));
  if (!ev.options().parameterisation.hasDoubleSupport()) return rows;  // impact, then SS
  for (double t : phaseTimes(e.motion.T_DS, rate))
    rows.push_back(sampleTrajectoryAt(ev, e, Phase::DoubleSupport, t));
  return rows;
}

TrajectoryRow sampleTrajectoryAt(const GaitEvaluator& ev, const GaitEvaluation<double>& e,
                                 Phase phase, double t) {
  if (!e.motion_computed) throw std::logic_error("sampleTrajectoryAt: the step motion is undefined");
  const GaitMotion<double>& mo = e.motion;
  const Model& m = ev.model();
  if (phase == Phase::DoubleSupport)
    return toRow(mo.T_SS + t, phase, detail::dsSample(m, ev.options(), mo, t));
  const double s = ssCoordinateAt(ev.ssGrid(), mo.ss_time, t);
  const double alpha = chebyshevToInterval(s, mo.alpha_iSS, mo.alpha_fSS);
  const double phi = ev.ssGrid().interpolate(mo.ss_phi, s);
  const detail::SsPathPoint<double> pt = detail::ssPathPoint(m, mo, alpha);
  double ad, add;
  detail::zeroDynamicsRates(pt, phi, mo, ev.options().f_min, ad, add);
  return toRow(t, phase, detail::ssSample(m, pt, ad, add));
}

std::string trajectoryCsv(const std::vector<TrajectoryRow>& rows) {
  std::ostringstream out;
  out << "t,phase,alpha,delta1,delta2,delta3,delta4,alphad,delta1d,delta2d,delta3d,delta4d,"
         "alphadd,delta1dd,delta2dd,delta3dd,delta4dd,gamma1,gamma2,gamma3,gamma4,"
         "R1x,R1z,R2x,R2z,x_swing,z_swing,x_com,z_com\n";
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
    out << '\n';
  }
  return out.str();
}

}  // namespace gaitopt
