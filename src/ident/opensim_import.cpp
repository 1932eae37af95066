#include "gaitopt/ident/opensim_import.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
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

Eigen::Vector2d point(const std::array<double, 2>& p) { return {p[0], p[1]}; }

// Segment angles of the planar model (thigh = pelvis_tilt + hip_flexion, shank = thigh ±
// knee_angle with the knee's flexion sign, all counter-clockwise seen from the right), the hip
// joint centre and the trunk line through the lumped pelvis + torso CoM, at the IK times; the
// geometry is the robot file's pelvis_frame.
Eigen::MatrixXd ikChannels(const OpenSimTable& ik, const OpenSimConventions& conv,
                           const PelvisFrame& g) {
  const double unit = ik.in_degrees ? kPi / 180.0 : 1.0;
  // The shank turns backwards (clockwise seen from the right) as the knee flexes.
  const double knee = conv.knee == KneeFlexion::Negative ? unit : -unit;
  const auto col = [&](const char* name) { return ik.column(conv.column(name)); };
  const Eigen::VectorXd tilt = unit * col("pelvis_tilt");
  const Eigen::VectorXd lumbar = unit * col("lumbar_extension");
  const Eigen::VectorXd tx = col("pelvis_tx"), ty = col("pelvis_ty");
  Eigen::MatrixXd c(ik.rows(), kChannels);
  c.col(kThighR) = tilt + unit * col("hip_flexion_r");
  c.col(kShankR) = c.col(kThighR) + knee * col("knee_angle_r");
  c.col(kThighL) = tilt + unit * col("hip_flexion_l");
  c.col(kShankL) = c.col(kThighL) + knee * col("knee_angle_l");
  const double trunk_mass = g.pelvis_mass + g.torso_mass;
  const Eigen::Vector2d hip_in_pelvis = point(g.hip);
  for (Eigen::Index k = 0; k < ik.rows(); ++k) {
    const Eigen::Vector2d hip = Eigen::Vector2d(tx(k), ty(k)) + rotated(tilt(k), hip_in_pelvis);
    c(k, kHipX) = hip.x();
    c(k, kHipZ) = hip.y();
    const Eigen::Vector2d com =
        (g.pelvis_mass * rotated(tilt(k), point(g.pelvis_com) - hip_in_pelvis) +
         g.torso_mass * (rotated(tilt(k), point(g.back) - hip_in_pelvis) +
                         rotated(tilt(k) + lumbar(k), point(g.torso_com)))) /
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
Eigen::VectorXd markerTrunkAngle(const TrcData& trc, const OpenSimConventions& o) {
  const Eigen::MatrixX2d line = markerMean(trc, o.shoulder_markers) - markerMean(trc, o.pelvis_markers);
  Eigen::VectorXd psi(line.rows());
  for (Eigen::Index k = 0; k < line.rows(); ++k) psi(k) = angleFromUp(line.row(k).transpose());
  return psi;
}

// Output times: the force-plate samples inside the IK record and the time window (no
// extrapolation).
std::vector<Eigen::Index> samplesInside(const OpenSimTable& grf, const OpenSimTable& ik,
                                        const std::optional<std::pair<double, double>>& window) {
  double lo = ik.values(0, 0) - 1e-6, hi = ik.values(ik.rows() - 1, 0) + 1e-6;
  if (window) lo = std::max(lo, window->first - 1e-9), hi = std::min(hi, window->second + 1e-9);
  std::vector<Eigen::Index> rows;
  for (Eigen::Index k = 0; k < grf.rows(); ++k)
    if (grf.values(k, 0) >= lo && grf.values(k, 0) <= hi) rows.push_back(k);
  if (rows.size() < 3) {
    throw DataError(grf.file, "time", grf.first_data_line,
                    "fewer than 3 force-plate samples inside the IK time range of " + ik.file +
                        (window ? " and the time window" : ""));
  }
  return rows;
}

std::string seconds(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", t);
  return buf;
}

// The longest run of samples in which a plate sees a foot: an overground trial's plates lose
// the feet before and after the walkway's plates. Samples outside it are dropped with a note.
std::vector<Eigen::Index> plateSpan(const OpenSimTable& grf, const std::vector<Eigen::Index>& rows,
                                    const OpenSimConventions& c, double threshold,
                                    std::vector<std::string>& notes) {
  const Eigen::VectorXd right = grf.column(c.right_plate + "vy"), left = grf.column(c.left_plate + "vy");
  std::size_t best = 0, best_length = 0;
  for (std::size_t k = 0; k < rows.size();) {
    std::size_t end = k;
    while (end < rows.size() && (right(rows[end]) > threshold || left(rows[end]) > threshold)) ++end;
    if (end - k > best_length) best = k, best_length = end - k;
    k = std::max(end, k + 1);
  }
  if (best_length < 3)
    throw DataError(grf.file, "", grf.first_data_line + int(rows.front()),
                    "no foot on a plate (vertical forces <= threshold) in the time window: "
                    "walking needs a foot on the ground");
  if (best_length == rows.size()) return rows;
  const double t0 = grf.values(rows[best], 0), t1 = grf.values(rows[best + best_length - 1], 0);
  notes.push_back("kept t = " + seconds(t0) + " .. " + seconds(t1) + " s, where the plates see a foot; " +
                  std::to_string(rows.size() - best_length) + " samples outside (no foot on a plate "
                  "or another span) dropped with their steps");
  return {rows.begin() + long(best), rows.begin() + long(best + best_length)};
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

// Plate surface height: the mean CoP height while the feet are loaded (an unloaded plate's CoP
// is meaningless).
double groundHeight(const ImportedTrial& trial) {
  double sum = 0.0;
  int n = 0;
  for (const ImportedLeg& leg : trial.legs)
    for (Eigen::Index k = 0; k < leg.cop.rows(); ++k)
      if (leg.contact[k]) sum += leg.cop(k, 1), ++n;
  return n ? sum / n : 0.0;
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

// f(side, k) at the samples of the middle half of each single support of `side` (the foot is
// at rest on the ground or the belt there).
template <class Sample>
std::vector<double> midStanceSamples(const ImportedTrial& trial, Sample&& f) {
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
        samples.push_back(f(side, j));
      k = end;
    }
  }
  return samples;
}

// Belt speed = −median horizontal velocity of the stance foot over the middle half of its
// single supports.
template <class Velocity>
std::optional<double> beltFromStanceFeet(const ImportedTrial& trial, Velocity&& velocity) {
  const std::vector<double> samples =
      midStanceSamples(trial, [&](BodySide s, Eigen::Index k) { return -velocity(s, k); });
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

// CoP x of leg 1 and leg 2; a leg without contact gets its ankle's x (the point foot).
void copColumns(ImportedTrial& trial, const RobotParams& robot) {
  const Eigen::Index n = trial.t.size();
  trial.cop_x.resize(n, 2);
  for (Eigen::Index k = 0; k < n; ++k) {
    const BodySide sides[2] = {trial.leg1[k], otherSide(trial.leg1[k])};
    for (int j = 0; j < 2; ++j) {
      const ImportedLeg& leg = trial.legs[int(sides[j])];
      trial.cop_x(k, j) = leg.contact[k] ? leg.cop(k, 0) : importedAnkle(trial, robot, sides[j], k).x();
    }
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
  if (!options.pelvis_frame)
    throw DataError(robot.source_file, "pelvis_frame", 0,
                    "missing: the import needs the hip and trunk geometry in the IK model's pelvis "
                    "frame (see configs/robot/human_subject01.yaml)");
  ImportedTrial trial;
  trial.conventions = resolveConventions(ik, grf, trc ? &*trc : nullptr, options.conventions);
  const OpenSimConventions& conv = trial.conventions;
  const std::vector<Eigen::Index> rows =
      plateSpan(grf, samplesInside(grf, ik, options.time_window), conv, options.contact_threshold,
                trial.notes);
  trial.t.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k) trial.t(Eigen::Index(k)) = grf.values(rows[k], 0);

  const SmoothingSpline kin =
      fitSpline(ik.time(), ikChannels(ik, conv, *options.pelvis_frame), options.cutoff_hz);
  trial.legs[0].thigh = sampled(kin, trial.t, kThighR);
  trial.legs[0].shank = sampled(kin, trial.t, kShankR);
  trial.legs[1].thigh = sampled(kin, trial.t, kThighL);
  trial.legs[1].shank = sampled(kin, trial.t, kShankL);
  trial.hip_x = sampled(kin, trial.t, kHipX);
  trial.hip_z = sampled(kin, trial.t, kHipZ);
  if (trc && options.trunk_from_markers) {
    trial.trunk = sampled(fitSpline(trc->time, markerTrunkAngle(*trc, conv), options.cutoff_hz),
                          trial.t, 0);
    trial.trunk_source = "markers";
  } else {
    trial.trunk = sampled(kin, trial.t, kTrunkModel);
    trial.trunk_source = "IK model CoM";
  }
  readPlate(grf, rows, conv.right_plate, options.contact_threshold, trial.legs[0]);
  readPlate(grf, rows, conv.left_plate, options.contact_threshold, trial.legs[1]);
  trial.ground_z = groundHeight(trial);
  trial.events = gaitEvents(trial, options.contact_threshold);
  labelLegs(trial, grf, rows);

  Eigen::MatrixXd heel_velocity;
  if (trc) {
    Eigen::MatrixXd heels(trc->time.size(), 2);
    for (int s = 0; s < 2; ++s) heels.col(s) = trc->marker(conv.heel_markers[s]).col(0);
    heel_velocity = fitSpline(trc->time, heels, options.cutoff_hz).evaluate(trial.t, 1);
  }
  const auto heel = [&](BodySide s, Eigen::Index k) { return heel_velocity(k, int(s)); };
  if (options.belt_speed) {
    trial.belt_speed = *options.belt_speed;
    trial.belt_source = "given";
  } else {
    std::optional<double> belt;
    if (trc) {
      belt = beltFromStanceFeet(trial, heel);
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
  if (trc) {
    std::vector<double> speed = midStanceSamples(
        trial, [&](BodySide s, Eigen::Index k) { return std::abs(heel(s, k) + trial.belt_speed); });
    if (!speed.empty()) trial.stance_heel_speed = median(speed);
  }
  removeBelt(trial);
  thesisCoordinates(trial);
  copColumns(trial, robot);
  return trial;
}

}  // namespace gaitopt
