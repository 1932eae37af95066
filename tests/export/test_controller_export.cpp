// Controller export: CSV round trip, the JSON polynomials against the samples, continuity of
// the physical motor angles across touchdown and lift-off, the torque split against the
// evaluator's Γ*.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/io/file_digest.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/model/joint_friction.hpp"
#include "test_default_gait.hpp"
#include "test_export_rows.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

namespace gaitopt::test {
namespace {

double polynomialAt(const YAML::Node& coefficients, double s) {
  double v = 0.0;
  for (std::size_t k = coefficients.size(); k-- > 0;) v = v * s + coefficients[k].as<double>();
  return v;
}

double bezierAt(const YAML::Node& b, double s) {  // de Casteljau
  std::vector<double> c;
  for (const auto& x : b) c.push_back(x.as<double>());
  for (std::size_t level = c.size(); level-- > 1;)
    for (std::size_t i = 0; i < level; ++i) c[i] = (1 - s) * c[i] + s * c[i + 1];
  return c[0];
}

}  // namespace

TEST_CASE("SHA-256 matches the FIPS 180-2 test vector", "[export]") {
  CHECK(sha256Hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256Hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST_CASE("Export CSV reads back to 1e-9", "[export]") {
  const DefaultGait f;
  REQUIRE(f.evaluation.motion_computed);
  ExportRequest req;
  req.steps = 3;
  req.rate = 400;
  req.first_stance = Leg::Right;
  const std::vector<ExportRow> rows = exportTrajectory(f.evaluator, f.evaluation, f.model, req);
  const double T = f.evaluation.T_SS + f.evaluation.T_DS;
  const auto fixed_rate = std::count_if(rows.begin(), rows.end(), [](const ExportRow& r) {
    return r.event == ExportEvent::None;
  });
  REQUIRE(static_cast<long>(fixed_rate) == static_cast<long>(std::floor(3 * T * 400)) + 1);
  ScratchDir dir("export");
  const std::string path = dir.fresh("walk") + ".csv";
  const ExportMetadata meta = exportMetadata(f.gait, f.evaluation, req);
  std::ofstream(path) << exportCsv(meta, rows);
  ExportCsvFile back = readExportCsv(path);
  CHECK(std::count(back.meta.at("units").begin(), back.meta.at("units").end(), ',') + 1 ==
        static_cast<long>(exportColumns().size()));
  back.meta.erase("units");
  CHECK(back.meta == meta);
  CHECK(back.meta.at("robot_sha256") == fileSha256(f.gait.robot_path));
  REQUIRE(back.rows.size() == rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) requireRowsEqual(back.rows[i], rows[i], 1e-9);
  // Stance alternates by step, starting with the requested leg; SS stance = leg 1.
  CHECK(rows.front().stance == Leg::Right);
  for (const ExportRow& r : rows)
    if (r.phase == Phase::SingleSupport)
      CHECK(r.stance == (r.step % 2 == 0 ? Leg::Right : Leg::Left));
}

TEST_CASE("Export CSV reader names the row and column of a bad cell", "[export]") {
  const DefaultGait f;
  ExportRequest req;
  req.rate = 50;
  std::string csv =
      exportCsv(exportMetadata(f.gait, f.evaluation, req),
                exportTrajectory(f.evaluator, f.evaluation, f.model, req));
  const std::size_t header_end = csv.find("\nt,") + 1;
  const std::size_t row1 = csv.find('\n', header_end) + 1;
  // The cell before the (k + 1)-th comma of row 1.
  const auto cell = [&](int k) {
    std::size_t begin = row1;
    for (int i = 0; i < k; ++i) begin = csv.find(',', begin) + 1;
    return std::pair{begin, csv.find(',', begin) - begin};
  };
  ScratchDir dir("export");
  const int line = static_cast<int>(std::count(csv.begin(), csv.begin() + row1, '\n')) + 1;
  for (const auto& [column, value, problem] :
       {std::tuple{8, "oops", "not a finite number: 'oops'"},
        {4, "3", "expected 0, 1 or 2, got '3'"}}) {
    REQUIRE(exportColumns()[column].first == (column == 8 ? "alpha" : "event"));
    std::string bad = csv;
    const auto [begin, size] = cell(column);
    bad.replace(begin, size, value);
    const std::string path = dir.fresh("bad") + ".csv";
    std::ofstream(path) << bad;
    requireConfigError([](const std::string& p) { readExportCsv(p); }, path,
                       exportColumns()[column].first, line, problem);
  }
}

TEST_CASE("Export CSV reader refuses a file of another schema version", "[export]") {
  const DefaultGait f;
  ExportRequest req;
  req.rate = 50;
  const std::string csv = exportCsv(exportMetadata(f.gait, f.evaluation, req),
                                    exportTrajectory(f.evaluator, f.evaluation, f.model, req));
  const std::size_t at = csv.find("# schema_version: 2\n");
  REQUIRE(at != std::string::npos);
  const int header = static_cast<int>(std::count(csv.begin(), csv.begin() + csv.find("\nt,"),
                                                 '\n')) + 2;
  ScratchDir dir("export");
  const std::string old = dir.fresh("v1") + ".csv";
  std::ofstream(old) << std::string(csv).erase(at, 20);
  requireConfigError([](const std::string& p) { readExportCsv(p); }, old, "schema_version",
                     header - 1, "written by an older gaitopt");
  const std::string v3 = dir.fresh("v3") + ".csv";
  std::ofstream(v3) << std::string(csv).replace(at, 20, "# schema_version: 3\n");
  requireConfigError([](const std::string& p) { readExportCsv(p); }, v3, "schema_version",
                     header, "schema version 3 is not supported");
}

TEST_CASE("Export JSON polynomials reproduce the sampled motor angles to 1e-9", "[export]") {
  const auto [rows, doc] = exportedJson(DefaultGait(), 300);
  REQUIRE(doc["samples"]["t"].size() == rows.size());
  const YAML::Node ss = doc["phases"]["SS"], ds = doc["phases"]["DS"];
  const double a0 = ss["alpha_start"].as<double>(), a1 = ss["alpha_end"].as<double>();
  const double b0 = ds["alpha_start"].as<double>(), b1 = ds["alpha_end"].as<double>();
  const double T_SS = ss["duration"].as<double>(), T_DS = ds["duration"].as<double>();
  int ss_count = 0, ds_count = 0;
  for (const ExportRow& r : rows) {
    // One step from the left leg: SS leg 1 is the left leg, DS leg 1 (front) the right one.
    REQUIRE(r.stance == (r.phase == Phase::SingleSupport ? Leg::Left : Leg::Right));
    CHECK(r.s == Approx((r.alpha - (r.phase == Phase::SingleSupport ? a0 : b0)) /
                        (r.phase == Phase::SingleSupport ? a1 - a0 : b1 - b0))
                     .margin(1e-12));
    if (r.phase == Phase::SingleSupport) {
      const double s = r.s;
      const char* names[] = {"phi_knee_stance", "phi_hip_stance", "phi_hip_swing",
                             "phi_knee_swing"};
      for (int j = 0; j < 4; ++j) {
        const YAML::Node p = ss["outputs"][names[j]];
        CHECK(polynomialAt(p["monomial"], s) == Approx(r.phi(j)).margin(1e-9));
        CHECK(bezierAt(p["bezier"], s) == Approx(r.phi(j)).margin(1e-9));
      }
      ++ss_count;
    } else {
      const double tau = (r.t - T_SS) / T_DS;
      CHECK(polynomialAt(ds["alpha_of_tau"]["monomial"], tau) == Approx(r.alpha).margin(1e-9));
      CHECK(bezierAt(ds["alpha_of_tau"]["bezier"], tau) == Approx(r.alpha).margin(1e-9));
      const double s = r.s;
      // In DS the front leg is leg 1: the right leg after a left-stance SS.
      CHECK(polynomialAt(ds["outputs"]["phi_knee_front"]["monomial"], s) ==
            Approx(r.phi(3)).margin(1e-9));
      CHECK(polynomialAt(ds["outputs"]["phi_hip_front"]["monomial"], s) ==
            Approx(r.phi(2)).margin(1e-9));
      CHECK(bezierAt(ds["outputs"]["phi_hip_front"]["bezier"], s) ==
            Approx(r.phi(2)).margin(1e-9));
      ++ds_count;
    }
  }
  CHECK(ss_count > 100);
  CHECK(ds_count >= 10);
}

TEST_CASE("Physical motor angles, hip and feet are continuous at touchdown and lift-off",
          "[export]") {
  const DefaultGait f;
  const GaitMotion<double>& mo = f.evaluation.motion;
  const auto at = [&](Phase ph, double t, int step, Leg leg1, double foot1_x) {
    return exportRow(f.model, sampleTrajectoryAt(f.evaluator, f.evaluation, ph, t), step, leg1,
                     foot1_x, 0.0);
  };
  // Touchdown of step 0: SS on the left leg ends, DS starts with the right leg in front.
  const ExportRow ss_end = at(Phase::SingleSupport, mo.T_SS, 0, Leg::Left, 0.0);
  const ExportRow ds_start = at(Phase::DoubleSupport, 0.0, 0, Leg::Right, mo.d);
  // Lift-off: DS ends, SS of step 1 starts on the right leg.
  const ExportRow ds_end = at(Phase::DoubleSupport, mo.T_DS, 0, Leg::Right, mo.d);
  const ExportRow ss_start = at(Phase::SingleSupport, 0.0, 1, Leg::Right, mo.d);
  for (const auto& [a, b] : {std::pair{ss_end, ds_start}, {ds_end, ss_start}}) {
    CHECK((a.phi - b.phi).lpNorm<Eigen::Infinity>() < 1e-9);
    CHECK((a.hip - b.hip).norm() < 1e-9);
    CHECK((a.foot_left - b.foot_left).norm() < 1e-9);
    CHECK((a.foot_right - b.foot_right).norm() < 1e-9);
    CHECK(a.trunk_angle == Approx(b.trunk_angle).margin(1e-9));
  }
  // The gait lands and lifts off with zero foot velocity and continuous joint speeds.
  CHECK((ss_end.phid - ds_start.phid).lpNorm<Eigen::Infinity>() < 1e-6);
  CHECK((ds_end.phid - ss_start.phid).lpNorm<Eigen::Infinity>() < 1e-6);
  CHECK(ss_end.foot_right(0) == Approx(mo.d).margin(1e-9));
  CHECK(std::abs(ss_end.foot_right(1)) < 1e-9);
}

TEST_CASE("Exported torques add up to the evaluator's Γ* plus the robot file's dry friction",
          "[export]") {
  const DefaultGait f;
  // With dry friction the evaluator's Γ* has the robot's Coulomb friction already, the same
  // smooth sign; without, viscous friction only and the export adds the rest.
  const bool add_coulomb = !f.gait.options.dry_friction;
  ExportRequest req;
  req.rate = 200;
  const double eps = f.gait.model_options.friction_smoothing;
  for (const ExportRow& e : exportTrajectory(f.evaluator, f.evaluation, f.model, req)) {
    const double t = e.phase == Phase::SingleSupport ? e.t : e.t - f.evaluation.T_SS;
    const TrajectoryRow r = sampleTrajectoryAt(f.evaluator, f.evaluation, e.phase, t);
    Vec4 expected = r.gamma_star;
    const Vec4 w = jointSpeeds(r.qd);
    for (int j = 0; add_coulomb && j < 4; ++j)
      expected(j) += f.model.coulomb(j) * std::tanh(w(j) / eps);
    const Vec4 physical = expected.reverse();  // one step: SS left (identity), DS right
    CHECK((e.tau - (e.phase == Phase::SingleSupport ? expected : physical))
              .lpNorm<Eigen::Infinity>() < 1e-8);
    if (e.phase == Phase::SingleSupport) CHECK(e.tau_contact.norm() == 0.0);
    CHECK((e.tau_inertial + e.tau_gravity + e.tau_contact + e.tau_friction - e.tau).norm() <
          1e-12);
  }
}

}  // namespace gaitopt::test
