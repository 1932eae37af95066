// import-opensim on a second person: the overground Rajagopal-family trial shipped in
// data/opensim-rajagopal-walk/ (IK+RRA .sto with path column names, per-side plate prefixes,
// knee_angle positive in flexion, a .trc whose header values are padded with empty fields).
#include <algorithm>
#include <catch2/catch.hpp>

#include <cmath>

#include "gaitopt/ident/opensim_analysis.hpp"
#include "gaitopt/ident/opensim_import.hpp"
#include "gaitopt/io/measured_data.hpp"
#include "gaitopt/io/opensim_conventions_file.hpp"
#include "gaitopt/io/opensim_table.hpp"
#include "gaitopt/io/opensim_trial_file.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "gaitopt/io/tab_text.hpp"
#include "gaitopt/io/trc_file.hpp"
#include "test_opensim_data.hpp"

using namespace gaitopt;
using namespace gaitopt::test;
using Catch::Matchers::Contains;

namespace {

const RobotParams& rajagopal() {
  static const RobotParams r = loadRobot(rajagopalRobot());
  return r;
}

const OpenSimImportFiles& files() {
  static const OpenSimImportFiles f{rajagopalIk(), rajagopalGrf(), rajagopalTrc(), rajagopalModel(), ""};
  return f;
}

const ImportedTrial& secondTrial() {
  static const ImportedTrial t = importOpenSimTrial(files(), rajagopal());
  return t;
}

bool stated(const ImportedTrial& t, const std::string& text) {
  for (const std::string& s : t.conventions.statements)
    if (s.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("second trial: the files OpenSim writes are read", "[opensim_io]") {
  // IK+RRA storage: header nColumns=40 over 32 columns named by coordinate paths.
  const OpenSimTable ik = readOpenSimTable(rajagopalIk());
  CHECK(ik.rows() == 1350);
  CHECK(ik.columns.size() == 32);
  CHECK_FALSE(ik.in_degrees);
  CHECK(ik.column("knee_angle_r")(0) == Approx(0.378135077733834).epsilon(1e-12));
  CHECK(ik.column("pelvis_ty")(0) == Approx(0.96796985).epsilon(1e-12));
  CHECK_THROWS_WITH(ik.column("knee"), Contains("missing"));
  // Header values padded with empty fields, millimetres.
  const TrcData trc = readTrcFile(rajagopalTrc());
  CHECK(trc.rate == 100.0);
  CHECK(trc.markers.size() == 41);
  CHECK(trc.time.size() == 238);
  CHECK(trc.marker("R.Shoulder")(0, 0) == Approx(-0.65263).epsilon(1e-12));
  const OpenSimTable grf = readOpenSimTable(rajagopalGrf());
  CHECK(grf.rows() == 4778);
  CHECK(grf.hasColumn("ground_force_l_vy"));
}

TEST_CASE("second trial: old-style headers and headers without inDegrees", "[opensim_io]") {
  ScratchDir dir("opensim_headers");
  const std::vector<std::string> grf = fileLines(rajagopalGrf());
  // grf_walk.mot: name, version=1, nRows=4778, nColumns=19, inDegrees=no, endheader.
  const std::string old_style =
      writeDamaged(dir, grf, {{2, "datacolumns 19"}, {3, "datarows 4778"}, {4, "range 0 2.3885"}, {5, "x"}}, ".mot");
  const OpenSimTable t = readOpenSimTable(old_style);
  CHECK(t.rows() == 4778);
  CHECK_FALSE(t.units_declared);
  const std::string truncated = writeDamaged(dir, grf, {{3, "datarows 4779"}, {5, "x"}}, ".mot");
  requireRowError([](const std::string& p) { return readOpenSimTable(p); }, truncated, 4785,
                  "the file has 4778 data rows but its header says datarows=4779");
  // An IK table must say its angle unit.
  const std::vector<std::string> ik = fileLines(rajagopalIk());
  const std::string no_flag = writeDamaged(dir, ik, {{2, "x"}}, ".sto");
  requireConfigError([](const std::string& p) { return readOpenSimRecording({p, rajagopalGrf(), ""}); },
                     no_flag, "inDegrees", 10, "the IK angles need inDegrees=yes or inDegrees=no");
}

TEST_CASE("second trial: conventions detected from the files and stated", "[opensim_import]") {
  const ImportedTrial& t = secondTrial();
  const OpenSimConventions& c = t.conventions;
  CHECK(c.right_plate == "ground_force_r_");
  CHECK(c.left_plate == "ground_force_l_");
  CHECK(c.knee == KneeFlexion::Positive);
  CHECK(c.pelvis_markers == std::vector<std::string>{"R.ASIS", "L.ASIS", "S2"});
  CHECK(c.shoulder_markers == std::vector<std::string>{"R.Shoulder", "L.Shoulder"});
  CHECK(stated(t, "detected from the column names"));
  CHECK(stated(t, "knee_angle_r range 0..2.44346 rad"));
  // The shipped treadmill trial: unnamed plates told apart by their centres of pressure.
  const RobotParams s01 = loadRobot(std::string(GAITOPT_SOURCE_DIR) + "/configs/robot/human_subject01.yaml");
  const ImportedTrial first = importOpenSimTrial({opensimIk(), opensimGrf(), opensimTrc()}, s01);
  CHECK(first.conventions.right_plate == "ground_force_");
  CHECK(first.conventions.knee == KneeFlexion::Negative);
  CHECK(stated(first, "detected from the centres of pressure"));
}

TEST_CASE("second trial: events of the plates, an overground walk at rest", "[opensim_import]") {
  const ImportedTrial& t = secondTrial();
  // Threshold crossings (20 N) of grf_walk.mot inside the IK record 0.45–1.799 s.
  const std::vector<std::pair<double, bool>> right{{1.024, false}, {1.411, true}};
  const std::vector<std::pair<double, bool>> left{{0.836, true}, {1.590, false}};
  std::vector<GaitEvent> r, l;
  for (const GaitEvent& e : t.events) (e.side == BodySide::Right ? r : l).push_back(e);
  REQUIRE(r.size() == 2);
  REQUIRE(l.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) {
    CHECK(r[k].time == Approx(right[k].first).margin(1e-3));
    CHECK(r[k].heel_strike == right[k].second);
    CHECK(l[k].time == Approx(left[k].first).margin(1e-3));
  }
  // Overground: the stance heels rest on the floor, so the "belt" is about zero.
  CHECK(std::abs(t.belt_speed) < 0.05);
  REQUIRE(t.stance_heel_speed);
  CHECK(*t.stance_heel_speed < 0.05);
  CHECK(t.notes.empty());
}

TEST_CASE("second trial: hip and knee moments follow OpenSim's with their sign", "[opensim_import]") {
  const ImportedTrial& t = secondTrial();
  const OpenSimTable id = readOpenSimTable(rajagopalId());
  const OpenSimAnalysis a = analyseImportedTrial(t, buildModel(rajagopal()), &id);
  REQUIRE(a.joints.size() == 4);
  for (const JointComparison& j : a.joints) {
    INFO(j.joint << " correlation " << j.correlation << ", RMS " << j.rms << " of " << j.reference_rms);
    CHECK(j.correlation > 0.9);
    CHECK(j.rms < 0.5 * j.reference_rms);
  }
  // The rocker fit stays near the roll-over-shape value 0.3 x leg length.
  CHECK(a.rocker.radius_all / a.rocker.leg_length > 0.15);
  CHECK(a.rocker.radius_all / a.rocker.leg_length < 0.6);
}

TEST_CASE("second trial: conventions from a file, contradictions refused", "[opensim_import]") {
  ScratchDir dir("opensim_conventions");
  const std::string wrong = dir.fresh("conv") + ".yaml";
  std::ofstream(wrong) << "knee_flexion: negative\n";
  OpenSimImportFiles f = files();
  f.model.clear();
  f.conventions = wrong;
  CHECK_THROWS_WITH(importOpenSimTrial(f, rajagopal()),
                    Contains(rajagopalIk()) && Contains("knee_angle_r") &&
                        Contains("conventions file says knee flexion is negative, the knee angles"));
  // The model's knee range contradicts it too.
  ConventionHints hints = readConventionsFile(wrong);
  CHECK_THROWS_WITH(addModelHints(rajagopalModel(), hints), Contains("contradicts the knee_flexion"));
  const std::string swapped = dir.fresh("conv") + ".yaml";
  std::ofstream(swapped) << "plates: {right: ground_force_l_, left: ground_force_r_}\n";
  f.conventions = swapped;
  CHECK_THROWS_WITH(importOpenSimTrial(f, rajagopal()), Contains("the plates are swapped"));
  const std::string unknown = dir.fresh("conv") + ".yaml";
  std::ofstream(unknown) << "markers: {pelvis: R.ASIS L.ASIS Sacrum}\n";
  f.conventions = unknown;
  CHECK_THROWS_WITH(importOpenSimTrial(f, rajagopal()), Contains("Sacrum") && Contains("missing"));
}

TEST_CASE("second trial: geometry from the robot file, time window, plate span", "[opensim_import]") {
  // The hip is 0.0887 m below the pelvis origin in this model, 0.0677 m in subject01's: the
  // robot file decides (pelvis tilt is below 3 degrees, so the heights differ by ~0.021 m).
  const RobotParams s01 = loadRobot(std::string(GAITOPT_SOURCE_DIR) + "/configs/robot/human_subject01.yaml");
  const ImportedTrial other = importOpenSimTrial(files(), s01);
  const Eigen::VectorXd dz = other.hip_z.v - secondTrial().hip_z.v;
  CHECK(dz.mean() == Approx(0.0210).margin(0.002));
  const std::string plain = std::string(GAITOPT_SOURCE_DIR) + "/configs/robot/rabbit_miossec.yaml";
  CHECK_THROWS_WITH(importOpenSimTrial(files(), loadRobot(plain)),
                    Contains(plain) && Contains("pelvis_frame") && Contains("missing"));

  ScratchDir robots("opensim_pelvis_frame");
  const std::string heavy = robots.fresh("robot") + ".yaml";
  const std::string robot_text = readFile(rajagopalRobot());
  std::ofstream(heavy) << replacedOnce(robot_text, "torso_mass: 38.7756", "torso_mass: 48.7756");
  const int torso_line = 1 + static_cast<int>(std::count(
                                 robot_text.begin(), robot_text.begin() + robot_text.find("torso_mass:"), '\n'));
  requireConfigError([](const std::string& p) { return loadRobot(p); }, heavy, "pelvis_frame.torso_mass", torso_line,
                     "pelvis_mass + torso_mass = 62.114 kg must be the trunk mass m3 = 52.114 kg");

  OpenSimImportOptions window;
  window.time_window = std::make_pair(0.9, 1.5);
  const ImportedTrial w = importOpenSimTrial(files(), rajagopal(), window);
  CHECK(w.t(0) >= 0.9);
  CHECK(w.t(w.t.size() - 1) <= 1.5);
  CHECK(w.t(0) == Approx(0.9).margin(1e-3));

  // No foot on the plates after 1.7 s (both vertical forces zeroed): that part is dropped.
  ScratchDir dir("opensim_span");
  std::vector<std::string> grf = fileLines(rajagopalGrf());
  for (std::size_t i = 7; i < grf.size(); ++i) {
    std::vector<std::string> f = splitTabFields(grf[i], "", 0);
    if (f.size() < 19 || std::stod(f[0]) <= 1.7) continue;
    f[2] = f[11] = "0";
    std::string row = f[0];
    for (std::size_t c = 1; c < f.size(); ++c) row += "\t" + f[c];
    grf[i] = row;
  }
  const std::string cut = writeDamaged(dir, grf, {}, ".mot");
  const ImportedTrial span = importOpenSimTrial({rajagopalIk(), cut, rajagopalTrc(), "", ""}, rajagopal());
  CHECK(span.t(span.t.size() - 1) == Approx(1.7).margin(1e-3));
  REQUIRE(span.notes.size() == 1);
  CHECK_THAT(span.notes[0], Contains("kept t = 0.45 .. 1.7 s"));
}

TEST_CASE("second trial: CSV with the centres of pressure, read back", "[opensim_import]") {
  const ImportedTrial& t = secondTrial();
  const RobotParams& robot = rajagopal();
  int single = 0;
  for (Eigen::Index k = 0; k < t.t.size(); ++k) {
    const BodySide s1 = t.leg1[k], s2 = otherSide(t.leg1[k]);
    // Leg 1 carries load: its CoP lies under its foot (heel to toes, within 0.25 m of the ankle).
    CHECK(std::abs(t.cop_x(k, 0) - importedAnkle(t, robot, s1, k).x()) < 0.25);
    if (t.double_support[k]) continue;
    ++single;
    CHECK(t.cop_x(k, 1) == importedAnkle(t, robot, s2, k).x());
  }
  CHECK(single > 0);
  ScratchDir dir("opensim_cop");
  const std::string path = dir.fresh("data") + ".csv";
  std::ofstream(path) << importedTrialCsv(t);
  const MeasuredData d = readMeasuredCsv(path);
  REQUIRE(d.has_cop);
  CHECK(d.cop[10][0] == Approx(t.cop_x(10, 0)).epsilon(1e-9));
  CHECK(d.cop[10][1] == Approx(t.cop_x(10, 1)).epsilon(1e-9));
}
