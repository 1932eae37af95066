#include "gaitopt/ident/opensim_import.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "gaitopt/ident/data_error.hpp"
#include "gaitopt/math/smoothing_spline.hpp"

namespace gaitopt {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Columns of the IK-rate kinematics that are smoothed together.
enum Channel { kThighR, kShankR, kThighL, kShankL, kHipX, kHipZ, kTrunkModel, kChannels };

Eigen::Vector2d rotated(double angle, const Eigen::Vector2d& v) {
  return {std::cos(angle) * v.x() - std::sin(angle) * v.y(),
          std::sin(angle) * v.x() + std::cos(angle) * v.y()};
}

// Angle of `v`, counter-clockwise from the upward vertical.
double angleFromUp(const Eigen::Vector2d& v) { return std::atan2(-v.x(), v.y()); }

// Segment angles of the planar model (README of the data: thigh = pelvis_tilt + hip_flexion,
// shank = thigh + knee_angle, all counter-clockwise seen from the right), the hip joint centre
// and the trunk line through the model's lumped pelvis + torso CoM, at the IK times.
Eigen::MatrixXd ikChannels(const OpenSimTable& ik, const OpenSimSubjectGeometry& g) {
  const double unit = ik.in_degrees ? kPi / 180.0 : 1.0;
  const Eigen::VectorXd tilt = unit * ik.column("pelvis_tilt");
  const Eigen::VectorXd lumbar = unit * ik.column("lumbar_extension");
  const Eigen::VectorXd tx = ik.column("pelvis_tx"), ty = ik.column("pelvis_ty");
  Eigen::MatrixXd c(ik.rows(), kChannels);
  c.col(kThighR) = tilt + unit * ik.column("hip_flexion_r");
  c.col(kShankR) = c.col(kThighR) + unit * ik.column("knee_angle_r");
  c.col(kThighL) = tilt + unit * ik.column("hip_flexion_l");
  c.col(kShankL) = c.col(kThighL) + unit * ik.column("knee_angle_l");
  const double trunk_mass = g.pelvis_mass + g.torso_mass;
  for (Eigen::Index k = 0; k < ik.rows(); ++k) {
    const Eigen::Vector2d hip = Eigen::Vector2d(tx(k), ty(k)) + rotated(tilt(k), g.hip_in_pelvis);
    c(k, kHipX) = hip.x();
    c(k, kHipZ) = hip.y();
    const Eigen::Vector2d com =
        (g.pelvis_mass * rotated(tilt(k), g.pelvis_com - g.hip_in_pelvis) +
         g.torso_mass * (rotated(tilt(k), g.back_in_pelvis - g.hip_in_pelvis) +
                         rotated(tilt(k) + lumbar(k), g.torso_com))) /
        trunk_mass;
    c(k, kTrunkModel) = angleFromUp(com);
  }
  return c;
}

double meanInterval(const Eigen::VectorXd& t) { return (t(t.size() - 1) - t(0)) / double(t.size() - 1); }

SmoothingSpline fitSpline(const Eigen::VectorXd& t, const Eigen::MatrixXd& y, double cutoff_hz) {
  return SmoothingSpline(t, y, smoothingLambdaForCutoff(meanInterval(t), cutoff_hz));
}

SmoothedTrajectory sampled(const SmoothingSpline& s, const Eigen::VectorXd& t, int channel) {
  return {s.evaluate(t, 0).col(channel), s.evaluate(t, 1).col(channel), s.evaluate(t, 2).col(channel)};
}

Eigen::MatrixX2d markerMean(const TrcData& trc, const std::vector<std::string>& names) {
  Eigen::MatrixX2d sum = Eigen::MatrixX2d::Zero(trc.time.size(), 2);
  for (const std::string& n : names) sum += trc.marker(n).leftCols<2>();
  return sum / double(names.size());
}

// Trunk line pelvis centroid → shoulder centroid (data README: within 3° of vertical, whereas
// the model's torso frame leans 13° forward), at the marker times.
Eigen::VectorXd markerTrunkAngle(const TrcData& trc, const OpenSimImportOptions& o) {
  const Eigen::MatrixX2d line = markerMean(trc, o.shoulder_markers) - markerMean(trc, o.pelvis_markers);
  Eigen::VectorXd psi(line.rows());
  for (Eigen::Index k = 0; k < line.rows(); ++k) psi(k) = angleFromUp(line.row(k).transpose());
  return psi;
}

// Output times: the force-plate samples inside the IK record (no extrapolation).
std::vector<Eigen::Index> samplesInside(const OpenSimTable& grf, const OpenSimTable& ik) {
  const double lo = ik.values(0, 0) - 1e-6, hi = ik.values(ik.rows() - 1, 0) + 1e-6;
  std::vector<Eigen::Index> rows;
  for (Eigen::Index k = 0; k < grf.rows(); ++k)
    if (grf.values(k, 0) >= lo && grf.values(k, 0) <= hi) rows.push_back(k);
  if (rows.size() < 3) {
    throw DataError(grf.file, "time", grf.first_data_line,
                      "fewer than 3 force-plate samples inside the IK time range of " + ik.file);
  }
  return rows;
}

void readPlate(const OpenSimTable& grf, const std::vector<Eigen::Index>& rows,
               const std::string& prefix, double threshold, ImportedLeg& leg) {
  const Eigen::VectorXd fx = grf.column(prefix + "vx"), fz = grf.column(prefix + "vy");
  const Eigen::VectorXd px = grf.column(prefix + "px"), pz = grf.column(prefix + "py");
  const Eigen::Index n = static_cast<Eigen::Index>(rows.size());
  leg.force.resize(n, 2);
  leg.cop.resize(n, 2);
  leg.contact.resize(rows.size());
  for (Eigen::Index k = 0; k < n; ++k) {
    leg.force.row(k) << fx(rows[k]), fz(rows[k]);
    leg.cop.row(k) << px(rows[k]), pz(rows[k]);
    leg.contact[k] = fz(rows[k]) > threshold;
  }
}

// Contact changes, timed where the vertical force crosses the threshold.
std::vector<GaitEvent> gaitEvents(const ImportedTrial& trial, double threshold) {
  std::vector<GaitEvent> events;
  for (BodySide side : {BodySide::Right, BodySide::Left}) {
    const ImportedLeg& leg = trial.legs[int(side)];
    for (Eigen::Index k = 1; k < trial.t.size(); ++k) {
      if (leg.contact[k] == leg.contact[k - 1]) continue;
      const double f0 = leg.force(k - 1, 1), f1 = leg.force(k, 1);
      const double w = (threshold - f0) / (f1 - f0);
      events.push_back({trial.t(k - 1) + w * (trial.t(k) - trial.t(k - 1)), side, bool(leg.contact[k])});
    }
  }
  std::sort(events.begin(), events.end(),
            [](const GaitEvent& a, const GaitEvent& b) { return a.time < b.time; });
  return events;
}

// Leg 1 of the thesis: the stance leg in SS; in DS the front leg, i.e. the one that struck
// last (before any heel strike: the leg that does not lift off first).
void labelLegs(ImportedTrial& trial, const OpenSimTable& grf, const std::vector<Eigen::Index>& rows) {
  const Eigen::Index n = trial.t.size();
  std::optional<BodySide> struck;
  std::size_t next_event = 0;
  int step = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    while (next_event < trial.events.size() && trial.events[next_event].time <= trial.t(k)) {
      if (trial.events[next_event].heel_strike) struck = trial.events[next_event].side;
      ++next_event;
    }
    const bool right = trial.legs[0].contact[k], left = trial.legs[1].contact[k];
    if (!right && !left) {
      throw DataError(grf.file, "", grf.first_data_line + int(rows[k]),
                        "neither foot in contact at t = " + std::to_string(trial.t(k)) +
                            " s (vertical forces <= threshold): walking needs a foot on the ground");
    }
    BodySide leg1 = right ? BodySide::Right : BodySide::Left;
    if (right && left) {
      if (struck) {
        leg1 = *struck;
      } else {
        const auto off = std::find_if(trial.events.begin(), trial.events.end(),
                                      [](const GaitEvent& e) { return !e.heel_strike; });
        leg1 = off == trial.events.end() ? BodySide::Right : otherSide(off->side);
      }
    }
    if (k > 0 && leg1 != trial.leg1.back()) ++step;
    trial.double_support.push_back(right && left);
    trial.leg1.push_back(leg1);
    trial.step.push_back(step);
  }
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// Belt speed = −median horizontal velocity of each foot over the middle half of its single
// supports (the foot is at rest on the belt there).
template <class Velocity>
std::optional<double> beltFromStanceFeet(const ImportedTrial& trial, Velocity&& velocity) {
  std::vector<double> samples;
  for (BodySide side : {BodySide::Right, BodySide::Left}) {
    const ImportedLeg& leg = trial.legs[int(side)];
    const ImportedLeg& other = trial.legs[int(otherSide(side))];
    Eigen::Index k = 0;
    const Eigen::Index n = trial.t.size();
    while (k < n) {
      if (!(leg.contact[k] && !other.contact[k])) { ++k; continue; }
      Eigen::Index end = k;
      while (end < n && leg.contact[end] && !other.contact[end]) ++end;
      for (Eigen::Index j = k + (end - k) / 4; j < end - (end - k) / 4; ++j)
        samples.push_back(-velocity(side, j));
      k = end;
    }
  }
  if (samples.empty()) return std::nullopt;
  return median(samples);
}

void removeBelt(ImportedTrial& trial) {
  const double v = trial.belt_speed;
  trial.hip_x.v += v * trial.t;
  trial.hip_x.d.array() += v;
  for (ImportedLeg& leg : trial.legs) leg.cop.col(0) += v * trial.t;
}

// (1.13) inverted: α = shank 1, δ1 = thigh 1 − shank 1 − π, δ2 = thigh 1 − π − trunk,
// δ3 = thigh 2 − thigh 1, δ4 = thigh 2 − shank 2 − π (straight knees: δ1 = δ4 = −π).
void thesisCoordinates(ImportedTrial& trial) {
  const Eigen::Index n = trial.t.size();
  trial.q.resize(n, 5);
  trial.qd.resize(n, 5);
  trial.qdd.resize(n, 5);
  trial.reactions.resize(n, 4);
  for (Eigen::Index k = 0; k < n; ++k) {
    const ImportedLeg& a = trial.legs[int(trial.leg1[k])];
    const ImportedLeg& b = trial.legs[int(otherSide(trial.leg1[k]))];
    const auto fill = [&](Eigen::MatrixXd& out, auto pick, double offset) {
      out.row(k) << pick(a.shank), pick(a.thigh) - pick(a.shank) - offset,
          pick(a.thigh) - offset - pick(trial.trunk), pick(b.thigh) - pick(a.thigh),
          pick(b.thigh) - pick(b.shank) - offset;
    };
    fill(trial.q, [k](const SmoothedTrajectory& s) { return s.v(k); }, kPi);
    fill(trial.qd, [k](const SmoothedTrajectory& s) { return s.d(k); }, 0.0);
    fill(trial.qdd, [k](const SmoothedTrajectory& s) { return s.dd(k); }, 0.0);
    trial.reactions.row(k) << a.force.row(k), b.force.row(k);
  }
}

}  // namespace

Eigen::Vector2d importedAnkle(const ImportedTrial& trial, const RobotParams& robot, BodySide side,
                              Eigen::Index k) {
  const ImportedLeg& leg = trial.legs[int(side)];
  const double th = leg.thigh.v(k), sh = leg.shank.v(k);
  return {trial.hip_x.v(k) + robot.l2 * std::sin(th) + robot.l1 * std::sin(sh),
          trial.hip_z.v(k) - robot.l2 * std::cos(th) - robot.l1 * std::cos(sh)};
}

double importedAnkleVelocityX(const ImportedTrial& trial, const RobotParams& robot, BodySide side,
                              Eigen::Index k) {
  const ImportedLeg& leg = trial.legs[int(side)];
  return trial.hip_x.d(k) + robot.l2 * std::cos(leg.thigh.v(k)) * leg.thigh.d(k) +
         robot.l1 * std::cos(leg.shank.v(k)) * leg.shank.d(k);
}

ImportedTrial importOpenSimTrial(const OpenSimRecording& recording, const RobotParams& robot,
                                 const OpenSimImportOptions& options) {
  const OpenSimTable& ik = recording.ik;
  const OpenSimTable& grf = recording.grf;
  const std::optional<TrcData>& trc = recording.trc;
  for (const auto& [file, n] :
       {std::pair<std::string, Eigen::Index>{ik.file, ik.rows()},
        {trc ? trc->file : std::string(), trc ? trc->time.size() : Eigen::Index(3)}}) {
    if (n < 3) throw DataError(file, "", 0, "fewer than 3 samples: nothing to smooth");
  }
  const std::vector<Eigen::Index> rows = samplesInside(grf, ik);
  ImportedTrial trial;
  trial.t.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k) trial.t(Eigen::Index(k)) = grf.values(rows[k], 0);

  const SmoothingSpline kin = fitSpline(ik.time(), ikChannels(ik, options.geometry), options.cutoff_hz);
  trial.legs[0].thigh = sampled(kin, trial.t, kThighR);
  trial.legs[0].shank = sampled(kin, trial.t, kShankR);
  trial.legs[1].thigh = sampled(kin, trial.t, kThighL);
  trial.legs[1].shank = sampled(kin, trial.t, kShankL);
  trial.hip_x = sampled(kin, trial.t, kHipX);
  trial.hip_z = sampled(kin, trial.t, kHipZ);
  if (trc && options.trunk_from_markers) {
    trial.trunk = sampled(fitSpline(trc->time, markerTrunkAngle(*trc, options), options.cutoff_hz),
                          trial.t, 0);
    trial.trunk_source = "markers";
  } else {
    trial.trunk = sampled(kin, trial.t, kTrunkModel);
    trial.trunk_source = "IK model CoM";
  }
  readPlate(grf, rows, options.right_plate, options.contact_threshold, trial.legs[0]);
  readPlate(grf, rows, options.left_plate, options.contact_threshold, trial.legs[1]);
  trial.ground_z = 0.5 * (trial.legs[0].cop.col(1).mean() + trial.legs[1].cop.col(1).mean());
  trial.events = gaitEvents(trial, options.contact_threshold);
  labelLegs(trial, grf, rows);

  if (options.belt_speed) {
    trial.belt_speed = *options.belt_speed;
    trial.belt_source = "given";
  } else {
    std::optional<double> belt;
    if (trc) {
      Eigen::MatrixXd heels(trc->time.size(), 2);
      for (int s = 0; s < 2; ++s) heels.col(s) = trc->marker(options.heel_markers[s]).col(0);
      const Eigen::MatrixXd v = fitSpline(trc->time, heels, options.cutoff_hz).evaluate(trial.t, 1);
      belt = beltFromStanceFeet(trial, [&](BodySide s, Eigen::Index k) { return v(k, int(s)); });
      trial.belt_source = "heel markers";
    } else {
      belt = beltFromStanceFeet(trial, [&](BodySide s, Eigen::Index k) {
        return importedAnkleVelocityX(trial, robot, s, k);
      });
      trial.belt_source = "IK ankle";
    }
    if (!belt) {
      throw DataError(grf.file, "", 0,
                        "no single support in the record: cannot estimate the belt speed; give it");
    }
    trial.belt_speed = *belt;
  }
  removeBelt(trial);
  thesisCoordinates(trial);
  return trial;
}

}  // namespace gaitopt
