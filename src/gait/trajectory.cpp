#include "gaitopt/gait/trajectory.hpp"

#include <cmath>
#include <stdexcept>

#include "gaitopt/gait/constraints/clearance.hpp"
#include "gaitopt/gait/constraints/torque_envelope.hpp"
#include "gaitopt/gait/phase_sample.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"

namespace gaitopt {
namespace {

// The joint points of the drawing, as origin + Σ_k e_k u(θ_k) like the model's own points
// (model.cpp): knee 1 after the stance tibia, knee 2 after the swing femur, the head at
// trunk_length along the trunk.
void addDrawingPoints(const Model& m, TrajectoryRow& r) {
  const RobotParams& p = m.robot;
  const ChainState<double> st = chainState(m, r.q, r.qd);
  const Vec5 knee1 = (Vec5() << -p.l1, 0, 0, 0, 0).finished();
  const Vec5 knee2 = (Vec5() << -p.l1, -p.l2, 0, p.l4, 0).finished();
  const Vec5 head = (Vec5() << -p.l1, -p.l2, p.trunk_length, 0, 0).finished();
  r.knee1 = chainPoint(knee1, st);
  r.hip = chainPoint(m.pinned.hip, st);
  r.knee2 = chainPoint(knee2, st);
  r.head = chainPoint(head, st);
}

TrajectoryRow toRow(const GaitEvaluator& ev, const GaitMotion<double>& mo, double t, Phase phase,
                    const PhaseSample<double>& s) {
  TrajectoryRow r = motionRow(t, phase, s);
  r.foot2 = s.foot2;
  r.com = s.com;
  const Model& m = ev.model();
  addDrawingPoints(m, r);
  r.omega = s.omega;
  r.gamma_max = jointTorqueLimits(m.robot.envelope, s.omega, ev.options().full_torque_envelope);
  r.sigma = pinnedTerms(m, s.q, s.qd).A.row(0).dot(s.qd);
  const double x = s.foot2(0) / mo.d;
  r.clearance = clearanceProfile(x, ev.options().clearance_height);  // (3.49)
  return r;
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
    return toRow(ev, mo, mo.T_SS + t, phase, dsSample(m, ev.options(), mo, t));
  const double s = ssCoordinateAt(ev.ssGrid(), mo.ss_time, t);
  const double alpha = chebyshevToInterval(s, mo.alpha_iSS, mo.alpha_fSS);
  const double phi = ev.ssGrid().interpolate(mo.ss_phi, s);
  const SsPathPoint<double> pt = ssPathPoint(m, mo, alpha);
  double ad, add;
  zeroDynamicsRates(pt, phi, mo, ev.options().f_min, ad, add);
  TrajectoryRow row = toRow(ev, mo, t, phase, ssSample(m, pt, ad, add));
  row.zd_potential = -0.5 * phi;  // Φ = σ² − σ_iSS² (3.14)
  return row;
}

}  // namespace gaitopt
