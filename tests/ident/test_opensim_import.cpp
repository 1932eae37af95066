// import-opensim on the shipped trial: events of the data README, leg-1/leg-2 relabelling at
// each heel strike, belt removal (stance feet at rest), angles against the markers;
// the point-foot analysis (torques vs OpenSim, rocker radius recovered from synthetic stances).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "gaitopt/ident/opensim_analysis.hpp"
#include "gaitopt/ident/opensim_import.hpp"
#include "gaitopt/io/opensim_table.hpp"
#include "gaitopt/io/opensim_trial_file.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "gaitopt/io/trc_file.hpp"
#include "gaitopt/math/smoothing_spline.hpp"
#include "test_opensim_data.hpp"

using namespace gaitopt;
using namespace gaitopt::test;
using Catch::Matchers::Contains;

namespace {

constexpr double kDeg = M_PI / 180.0;

const RobotParams& human() {
  static const RobotParams r = loadRobot(std::string(GAITOPT_SOURCE_DIR) + "/configs/robot/human_subject01.yaml");
  return r;
}

const ImportedTrial& shippedTrial() {
  static const ImportedTrial t = importOpenSimTrial({opensimIk(), opensimGrf(), opensimTrc()}, human());
  return t;
}

// Angle of the marker line a → b, counter-clockwise from the downward vertical, per frame.
Eigen::VectorXd markerLineAngle(const TrcData& trc, const std::string& a, const std::string& b) {
  const Eigen::MatrixX3d d = trc.marker(b) - trc.marker(a);
  Eigen::VectorXd out(d.rows());
  for (Eigen::Index k = 0; k < d.rows(); ++k) out(k) = std::atan2(d(k, 0), -d(k, 1));
  return out;
}

double stddev(const std::vector<double>& v) {
  const Eigen::Map<const Eigen::VectorXd> x(v.data(), Eigen::Index(v.size()));
  return std::sqrt((x.array() - x.mean()).square().mean());
}

}  // namespace

TEST_CASE("import: gait events are those of the data README", "[opensim_import]") {
  const ImportedTrial& t = shippedTrial();
  struct Expected { double time; BodySide side; bool hs; };
  const Expected expected[] = {{0.165, BodySide::Right, false}, {0.618, BodySide::Right, true},
                               {0.788, BodySide::Left, false},  {1.247, BodySide::Left, true},
                               {1.410, BodySide::Right, false}, {1.853, BodySide::Right, true},
                               {2.018, BodySide::Left, false},  {2.460, BodySide::Left, true}};
  REQUIRE(t.events.size() == 8);
  for (std::size_t i = 0; i < 8; ++i) {
    INFO("event " << i);
    CHECK(t.events[i].time == Approx(expected[i].time).margin(2.5e-3));  // 1.5 samples at 600 Hz
    CHECK(t.events[i].side == expected[i].side);
    CHECK(t.events[i].heel_strike == expected[i].hs);
  }
  CHECK(t.t.size() == 1501);
  CHECK(t.double_support.front());
}

TEST_CASE("import: leg 1 is the stance leg in SS, the front leg in DS, relabelled at heel strikes",
          "[opensim_import]") {
  const ImportedTrial& t = shippedTrial();
  int relabellings = 0;
  for (Eigen::Index k = 0; k < t.t.size(); ++k) {
    const BodySide l1 = t.leg1[k], l2 = otherSide(l1);
    INFO("t = " << t.t(k));
    CHECK(t.legs[int(l1)].contact[k]);
    CHECK(t.double_support[k] == bool(t.legs[int(l2)].contact[k]));
    if (t.double_support[k]) {
      CHECK(importedAnkle(t, human(), l1, k).x() > importedAnkle(t, human(), l2, k).x());
    }
    // q of (1.13) gives back the physical angles of the labelled legs.
    CHECK(t.q(k, 0) == Approx(t.legs[int(l1)].shank.v(k)).margin(1e-12));
    CHECK(t.q(k, 0) + t.q(k, 1) + t.q(k, 3) - t.q(k, 4) ==
          Approx(t.legs[int(l2)].shank.v(k)).margin(1e-12));
    CHECK(t.reactions(k, 3) == t.legs[int(l2)].force(k, 1));
    if (k == 0 || t.leg1[k] == t.leg1[k - 1]) continue;
    ++relabellings;
    CHECK(t.step[k] == t.step[k - 1] + 1);
    // Relabelling: the new stance shank α was leg 2's shank one sample before (θ5 + π/2).
    CHECK(t.q(k, 0) == Approx(t.q(k - 1, 0) + t.q(k - 1, 1) + t.q(k - 1, 3) - t.q(k - 1, 4)).margin(0.01));
    // δ3 changes sign with the roles of the thighs.
    CHECK(t.q(k, 3) == Approx(-t.q(k - 1, 3)).margin(0.01));
    // It happens at a heel strike of the new leg 1.
    bool at_strike = false;
    for (const GaitEvent& e : t.events)
      at_strike |= e.heel_strike && e.side == t.leg1[k] && std::abs(e.time - t.t(k)) < 2e-3;
    CHECK(at_strike);
  }
  CHECK(relabellings == 4);
}

TEST_CASE("import: after belt removal the stance foot is at rest", "[opensim_import]") {
  const ImportedTrial& t = shippedTrial();
  CHECK(t.belt_source == "heel markers");
  CHECK(t.belt_speed == Approx(1.123).margin(0.01));  // data README: right 1.125, left 1.121
  const TrcData trc = readTrcFile(opensimTrc());
  Eigen::MatrixXd heels(trc.time.size(), 2);
  heels.col(0) = trc.marker("R.Heel").col(0);
  heels.col(1) = trc.marker("L.Heel").col(0);
  const Eigen::MatrixXd v = SmoothingSpline(trc.time, heels, smoothingLambdaForCutoff(1.0 / 60, 6.0))
                                .evaluate(t.t, 1);
  std::vector<double> heel, ankle;
  for (Eigen::Index k = 0; k < t.t.size(); ++k) {
    if (t.double_support[k]) continue;
    // Middle of single support: 0.15 s from either end of it.
    if (t.double_support[std::max<Eigen::Index>(0, k - 90)] ||
        t.double_support[std::min<Eigen::Index>(t.t.size() - 1, k + 90)])
      continue;
    const BodySide s = t.leg1[k];
    heel.push_back(std::abs(v(k, int(s)) + t.belt_speed));
    ankle.push_back(std::abs(importedAnkleVelocityX(t, human(), s, k)));
  }
  REQUIRE(heel.size() > 300);
  std::sort(heel.begin(), heel.end());
  std::sort(ankle.begin(), ankle.end());
  CHECK(heel[heel.size() / 2] < 0.03);  // median |v| of the stance heel [m/s]
  // The five-link chain's ankle (IK angles, the lengths lump-osim takes from the scaled model)
  // stays on the heel in mid-stance as well (a femur 58 mm short made it creep by 0.1 m/s).
  CHECK(ankle[ankle.size() / 2] < 0.03);
  // Given belt speed: used as is.
  OpenSimImportOptions o;
  o.belt_speed = 1.0;
  const ImportedTrial given = importOpenSimTrial({opensimIk(), opensimGrf(), ""}, human(), o);
  CHECK(given.belt_source == "given");
  CHECK(given.hip_x.d.mean() == Approx(t.hip_x.d.mean() - (t.belt_speed - 1.0)).margin(1e-9));
  // Without markers: estimated from the IK ankle.
  const ImportedTrial ik_only = importOpenSimTrial({opensimIk(), opensimGrf(), ""}, human());
  CHECK(ik_only.belt_source == "IK ankle");
  CHECK(ik_only.belt_speed == Approx(t.belt_speed).margin(0.03));
}

TEST_CASE("import: segment angles against the markers", "[opensim_import]") {
  const ImportedTrial& t = shippedTrial();
  const TrcData trc = readTrcFile(opensimTrc());
  // Trunk: the pelvis-to-shoulder line, docs/commands/import-opensim.md: −0.3° … +3.1° forward, mean 1.2° forward.
  CHECK(t.trunk_source == "markers");
  CHECK(t.trunk.v.mean() == Approx(-1.24 * kDeg).margin(0.1 * kDeg));
  CHECK(t.trunk.v.maxCoeff() < 0.5 * kDeg);
  CHECK(t.trunk.v.minCoeff() > -3.3 * kDeg);
  // Shank and thigh: the IK angle follows the rotation of each marker cluster up to
  // soft-tissue motion (a few degrees).
  const struct { BodySide side; const char *a, *b; bool shank; } lines[] = {
      {BodySide::Right, "R.Shank.Upper", "R.Shank.Rear", true},
      {BodySide::Left, "L.Shank.Upper", "L.Shank.Rear", true},
      {BodySide::Right, "R.Thigh.Upper", "R.Thigh.Rear", false},
      {BodySide::Left, "L.Thigh.Upper", "L.Thigh.Rear", false}};
  for (const auto& l : lines) {
    const Eigen::VectorXd marker = markerLineAngle(trc, l.a, l.b);
    std::vector<double> diff;
    for (Eigen::Index f = 0; f < trc.time.size(); ++f) {
      const Eigen::Index k = 10 * f;  // 600 Hz samples at the 60 Hz frames
      REQUIRE(t.t(k) == Approx(trc.time(f)).margin(1e-3));
      const ImportedLeg& leg = t.legs[int(l.side)];
      diff.push_back((l.shank ? leg.shank.v(k) : leg.thigh.v(k)) - marker(f));
    }
    INFO(l.a << " -> " << l.b);
    CHECK(stddev(diff) < 3.5 * kDeg);
  }
  // Without markers the trunk line goes through the model's lumped pelvis + torso CoM, whose
  // direction from the hip agrees with the marker line on average, unlike the torso frame
  // (13° forward, data README).
  const ImportedTrial ik_only = importOpenSimTrial({opensimIk(), opensimGrf(), ""}, human());
  CHECK(ik_only.trunk_source == "IK model CoM");
  CHECK(ik_only.trunk.v.mean() == Approx(t.trunk.v.mean()).margin(3.0 * kDeg));
  OpenSimImportOptions model_trunk;
  model_trunk.trunk_from_markers = false;
  const ImportedTrial with_trc = importOpenSimTrial({opensimIk(), opensimGrf(), opensimTrc()}, human(), model_trunk);
  CHECK(with_trc.trunk_source == "IK model CoM");
  CHECK(with_trc.belt_source == "heel markers");
  CHECK(with_trc.trunk.v.isApprox(ik_only.trunk.v));
}

TEST_CASE("analysis: five-link torques follow OpenSim's hip and knee moments", "[opensim_import]") {
  const OpenSimTable id = readOpenSimTable(opensimId());
  const OpenSimAnalysis a = analyseImportedTrial(shippedTrial(), buildModel(human()), &id);
  REQUIRE(a.joints.size() == 4);
  for (const JointComparison& j : a.joints) {
    INFO(j.joint);
    CHECK(j.samples > 130);
    CHECK(j.correlation > 0.95);
    CHECK(j.rms < 0.35 * j.reference_rms);
  }
  // The point foot needs the moment the measured reaction has about the ankle.
  CHECK(a.alpha_cop_correlation > 0.7);
  CHECK(a.single_support_samples > 900);
}

TEST_CASE("rocker radius: recovered from synthetic rolling stances, 0 for a point foot",
          "[opensim_import]") {
  std::mt19937 rng(11);
  std::normal_distribution<double> cop_noise(0.0, 0.004);  // 4 mm force-plate CoP noise
  const auto stances = [&](double radius) {
    std::vector<StanceSamples> out;
    for (int s = 0; s < 4; ++s) {
      StanceSamples st;
      st.side = s % 2 ? BodySide::Left : BodySide::Right;
      const int n = 360;
      st.shank.resize(n);
      st.cop_x.resize(n);
      st.weight.resize(n);
      const double start = 0.3 + 0.02 * s, x0 = 0.4 * s;
      for (int i = 0; i < n; ++i) {
        const double u = double(i) / (n - 1);
        st.shank(i) = start - 0.65 * u + 0.03 * std::sin(3 * M_PI * u);  // shank turns forward
        // A rolling arc: the contact advances by r per radian of shank rotation.
        st.cop_x(i) = x0 + radius * (start - st.shank(i)) + cop_noise(rng);
        st.weight(i) = 50.0 + 700.0 * std::sin(M_PI * u);
      }
      out.push_back(st);
    }
    return out;
  };
  const std::vector<StanceSamples> rolling = stances(0.27);
  CHECK(fitRockerRadius(rolling) == Approx(0.27).epsilon(0.05));
  CHECK(rockerCopRms(rolling, fitRockerRadius(rolling)) < 0.006);
  CHECK(rockerCopRms(rolling, 0.0) > 0.03);
  const std::vector<StanceSamples> point = stances(0.0);
  CHECK(std::abs(fitRockerRadius(point)) < 0.01);
}

TEST_CASE("analysis: rocker radius of the shipped trial, held out across legs", "[opensim_import]") {
  const OpenSimAnalysis a = analyseImportedTrial(shippedTrial(), buildModel(human()), nullptr);
  const RockerFootReport& r = a.rocker;
  CHECK(r.stances_right == 2);
  CHECK(r.stances_left == 2);
  // Both legs roll: a radius of the order of the roll-over-shape value, similar on both sides.
  CHECK(r.radius_right == Approx(r.radius_left).epsilon(0.15));
  CHECK(r.radius_all > 0.5 * r.literature_radius);
  CHECK(r.radius_all < 2.0 * r.literature_radius);
  CHECK(r.holdout_gain_pct > 50.0);
  CHECK(r.leg_length == Approx(0.97).margin(0.05));
}

TEST_CASE("analysis: static one-leg stance gives the hand-computed distal joint torques",
          "[opensim_import]") {
  // Standing still on the right leg, the ground pushing M g straight up under the body's CoM.
  const RobotParams& r = human();
  const Model model = buildModel(r);
  const double g = r.gravity, M = model.total_mass;
  const double th[2] = {-0.15, 0.35}, sh[2] = {0.1, 0.05}, psi = -0.08;  // right, left
  const Eigen::Vector2d hip(0.3, 0.9);
  const auto down = [](double a) { return Eigen::Vector2d(std::sin(a), -std::cos(a)); };
  Eigen::Vector2d knee[2], G_femur[2], G_tibia[2];
  Eigen::Vector2d com = Eigen::Vector2d::Zero();  // Σ m_i G_i / M
  for (int s = 0; s < 2; ++s) {
    knee[s] = hip + r.l2 * down(th[s]);
    G_femur[s] = hip + r.s[1] * down(th[s]);
    G_tibia[s] = knee[s] + r.s[0] * down(sh[s]);
    com += r.mass[1] * G_femur[s] + r.mass[0] * G_tibia[s];
  }
  com += r.mass[2] * (hip + r.s[2] * Eigen::Vector2d(-std::sin(psi), std::cos(psi)));
  com /= M;
  ImportedTrial t;
  const int n = 3;
  t.t = Eigen::VectorXd::LinSpaced(n, 0.0, 0.02);
  const auto constant = [n](double v) {
    return SmoothedTrajectory{Eigen::VectorXd::Constant(n, v), Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)};
  };
  for (int s = 0; s < 2; ++s) {
    ImportedLeg& leg = t.legs[s];
    leg.thigh = constant(th[s]);
    leg.shank = constant(sh[s]);
    leg.force = Eigen::MatrixX2d::Zero(n, 2);
    leg.cop = Eigen::MatrixX2d::Zero(n, 2);
    leg.contact.assign(n, s == 0);
  }
  t.legs[0].force.col(1).setConstant(M * g);
  t.legs[0].cop.col(0).setConstant(com.x());
  t.trunk = constant(psi);
  t.hip_x = constant(hip.x());
  t.hip_z = constant(hip.y());
  t.leg1.assign(n, BodySide::Right);
  t.step.assign(n, 0);
  t.double_support.assign(n, false);
  Eigen::RowVectorXd q(5);  // (1.13) as documented in docs/conventions.md
  q << sh[0], th[0] - sh[0] - M_PI, th[0] - M_PI - psi, th[1] - th[0], th[1] - sh[1] - M_PI;
  t.q = q.replicate(n, 1);
  t.qd = Eigen::MatrixXd::Zero(n, 5);
  t.qdd = Eigen::MatrixXd::Zero(n, 5);
  const Eigen::MatrixX4d torque = importedJointTorques(t, model);
  const auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& f) { return a.x() * f.y() - a.y() * f.x(); };
  const Eigen::Vector2d w1(0, -r.mass[0] * g), w2(0, -r.mass[1] * g), ground(0, M * g);
  const Eigen::Vector2d cop(com.x(), 0.0);
  // Moment (counter-clockwise) the joint must put on its distal links; Γ acts on them as −Γ.
  const double knee_stance = -(cross(G_tibia[0] - knee[0], w1) + cross(cop - knee[0], ground));
  const double hip_stance = -(cross(G_tibia[0] - hip, w1) + cross(G_femur[0] - hip, w2) + cross(cop - hip, ground));
  const double hip_swing = -(cross(G_tibia[1] - hip, w1) + cross(G_femur[1] - hip, w2));
  const double knee_swing = -cross(G_tibia[1] - knee[1], w1);
  for (int k = 0; k < n; ++k) {
    CHECK(torque(k, 0) == Approx(-knee_stance).margin(1e-9));
    CHECK(torque(k, 1) == Approx(-hip_stance).margin(1e-9));
    CHECK(torque(k, 2) == Approx(-hip_swing).margin(1e-9));
    CHECK(torque(k, 3) == Approx(-knee_swing).margin(1e-9));
  }
  CHECK(std::abs(knee_stance) > 1.0);  // a case that can fail
}
