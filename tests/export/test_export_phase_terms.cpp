// Controller export, phase terms: the feedforward decomposition Γ = B s̈ + C ṡ² + G + K + F
// recomposes every row and, at other phase rates, equals the inverse dynamics of the
// time-scaled motion; rows at the exact touchdown and lift-off instants; the high-gear rotor
// model's feedforward; the JSON feedforward tables against the rows.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>

#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"
#include "test_default_gait.hpp"
#include "test_export_rows.hpp"

namespace gaitopt::test {
namespace {

Vec4 toLeg1(const Vec4& physical, Leg leg1) {
  return leg1 == Leg::Left ? physical : Vec4(physical.reverse());
}

// Start of the step's SS in a cyclic export.
double stepStart(const ShippedGait& f, int step) {
  return step * (f.evaluation.T_SS + f.evaluation.T_DS);
}

TrajectoryRow plannedRow(const ShippedGait& f, const ExportRow& e) {
  const double local = e.t - stepStart(f, e.step);
  return sampleTrajectoryAt(f.evaluator, f.evaluation, e.phase,
                            e.phase == Phase::SingleSupport ? local : local - f.evaluation.T_SS);
}

std::vector<ExportRow> cyclicRows(const ShippedGait& f, const Model& model, int steps,
                                  double rate) {
  ExportRequest req;
  req.steps = steps;
  req.rate = rate;
  return exportTrajectory(f.evaluator, f.evaluation, model, req);
}

}  // namespace

TEST_CASE("Exported feedforward recomposes as B sdd + C sd^2 + G + K + F at every row",
          "[export]") {
  for (const char* shipped : {"configs/gait/default_step.yaml",
                              "configs/gait/chevallereau_aoustin_0.75_impact.yaml"}) {
    INFO(shipped);
    const ShippedGait f(shipped);
    REQUIRE(f.evaluation.motion_computed);
    double worst = 0.0;
    for (const ExportRow& r : cyclicRows(f, f.model, 2, 500)) {
      const Vec4 parts[] = {Vec4(r.tau_B * r.sdd), Vec4(r.tau_C * r.sd * r.sd), r.tau_gravity,
                            r.tau_contact, r.tau_friction};
      Vec4 sum = Vec4::Zero();
      double scale = 0.0;
      for (const Vec4& p : parts) {
        sum += p;
        scale = std::max(scale, p.lpNorm<Eigen::Infinity>());
      }
      worst = std::max(worst, (sum - r.tau).lpNorm<Eigen::Infinity>() / scale);
      // B s̈ + C ṡ² is the inertial part computed from the planned q̈ directly.
      CHECK((parts[0] + parts[1] - r.tau_inertial).lpNorm<Eigen::Infinity>() <= 1e-9 * scale);
    }
    CHECK(worst <= 1e-9);
  }
}

TEST_CASE("The decomposition at other phase rates is the inverse dynamics of the time-scaled "
          "motion (SS)", "[export]") {
  const DefaultGait f;
  int checked = 0;
  for (const ExportRow& e : cyclicRows(f, f.model, 2, 400)) {
    if (e.phase != Phase::SingleSupport) continue;
    // Path derivatives from the planned motion itself: q̇ = q_s ṡ, q̈ = q_s s̈ + q_ss ṡ².
    const TrajectoryRow r = plannedRow(f, e);
    REQUIRE(std::abs(e.sd) > 0.1);
    const Vec5 qs = r.qd / e.sd, qss = (r.qdd - qs * e.sdd) / (e.sd * e.sd);
    for (const auto& [lambda, extra] : {std::pair{0.7, 0.0}, {1.3, 0.0}, {1.0, 2.5}}) {
      const double sd = lambda * e.sd, sdd = lambda * lambda * e.sdd + extra;
      const Vec5 qd = qs * sd, qdd = qs * sdd + qss * sd * sd;
      const Vec4 expected =
          inverseDynamicsSS(f.model, r.q, qd, qdd, SignMode::Smooth).gamma_star;
      const Vec4 friction = frictionTorque(f.model, jointSpeeds(qd), SignMode::Smooth);
      const Vec4 recomposed =
          toLeg1(Vec4(e.tau_B * sdd + e.tau_C * sd * sd + e.tau_gravity), e.stance) + friction;
      CHECK((recomposed - expected).lpNorm<Eigen::Infinity>() <=
            1e-8 * (1.0 + expected.lpNorm<Eigen::Infinity>()));
    }
    ++checked;
  }
  CHECK(checked > 300);
}

TEST_CASE("Export rows at the exact touchdown and lift-off instants", "[export]") {
  const DefaultGait f;
  const double T_SS = f.evaluation.T_SS, T_DS = f.evaluation.T_DS;
  const std::vector<ExportRow> rows = cyclicRows(f, f.model, 3, 250);
  std::vector<ExportRow> events;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i > 0) CHECK(rows[i].t >= rows[i - 1].t);
    CHECK(rows[i].s >= -1e-9);
    CHECK(rows[i].s <= 1.0 + 1e-9);
    if (rows[i].event != ExportEvent::None) events.push_back(rows[i]);
  }
  // 3 touchdowns and 2 lift-offs between them, each the ending and the starting phase's row.
  REQUIRE(events.size() == 10);
  for (int k = 0; k < 5; ++k) {
    const ExportRow& end = events[2 * k];
    const ExportRow& start = events[2 * k + 1];
    const int step = k / 2;
    const bool touchdown = k % 2 == 0;
    const double t = stepStart(f, step) + T_SS + (touchdown ? 0.0 : T_DS);
    CHECK(end.event == (touchdown ? ExportEvent::Touchdown : ExportEvent::LiftOff));
    CHECK(start.event == end.event);
    CHECK(end.t == Approx(t).margin(1e-12));
    CHECK(start.t == end.t);
    CHECK(end.phase == (touchdown ? Phase::SingleSupport : Phase::DoubleSupport));
    CHECK(start.phase == (touchdown ? Phase::DoubleSupport : Phase::SingleSupport));
    CHECK(end.step == step);
    CHECK(start.step == (touchdown ? step : step + 1));
    CHECK(end.s == Approx(1.0).margin(1e-9));
    CHECK(start.s == Approx(0.0).margin(1e-9));
    // The physical motor angles are continuous across the event.
    CHECK((end.phi - start.phi).lpNorm<Eigen::Infinity>() < 1e-9);
  }
  std::size_t fixed = 0;
  for (const ExportRow& r : rows) fixed += r.event == ExportEvent::None ? 1 : 0;
  CHECK(fixed == static_cast<std::size_t>(std::floor(3 * (T_SS + T_DS) * 250)) + 1);
}

TEST_CASE("With the high-gear rotor the feedforward is that model's inverse dynamics",
          "[export]") {
  const DefaultGait f;
  REQUIRE(f.model.options.rotor == RotorModel::Exact);
  ModelOptions options = f.gait.model_options;
  options.rotor = RotorModel::HighGear;
  const Model high_gear = buildModel(f.gait.robot, options);
  const std::vector<ExportRow> hg = cyclicRows(f, high_gear, 2, 400);
  const std::vector<ExportRow> exact = cyclicRows(f, f.model, 2, 400);
  REQUIRE(hg.size() == exact.size());
  double squares = 0.0;
  int ss = 0;
  for (std::size_t i = 0; i < hg.size(); ++i) {
    squares += (hg[i].tau - exact[i].tau).squaredNorm();
    if (hg[i].phase != Phase::SingleSupport) continue;
    const TrajectoryRow r = plannedRow(f, hg[i]);
    const Vec4 expected =
        inverseDynamicsSS(high_gear, r.q, r.qd, r.qdd, SignMode::Smooth).gamma_star;
    CHECK((toLeg1(hg[i].tau, hg[i].stance) - expected).lpNorm<Eigen::Infinity>() <= 1e-9);
    ++ss;
  }
  CHECK(ss > 300);
  // The rotor terms the high-gear model drops are not negligible for RABBIT (gear ratio 50).
  CHECK(std::sqrt(squares / (4.0 * hg.size())) > 0.05);
}

TEST_CASE("JSON feedforward tables match the rows within their stated interpolation error",
          "[export]") {
  const auto [rows, doc] = exportedJson(DefaultGait(), 300);
  CHECK(doc["schema_version"].as<int>() == 2);
  CHECK(doc["feedforward"]["rotor_model"].as<std::string>() == "exact");
  for (const ExportRow& r : rows) {
    const YAML::Node phase = doc["phases"][r.phase == Phase::SingleSupport ? "SS" : "DS"];
    const YAML::Node table = phase["feedforward_table"];
    const int n = static_cast<int>(table["s"].size()) - 1;
    const int k = std::min(n - 1, std::max(0, static_cast<int>(std::floor(r.s * n))));
    const double u = r.s * n - k;
    const Vec4 B = toLeg1(r.tau_B, r.stance), G = toLeg1(r.tau_gravity, r.stance);
    for (const auto& [name, value] : {std::pair{"B", B}, {"G", G}}) {
      const double bound = 2.0 * table["linear_interpolation_max_error"][name].as<double>() + 1e-12;
      for (int j = 0; j < 4; ++j) {
        const YAML::Node v = table[name][phase["joint_order"][j].as<std::string>()];
        const double interpolated = (1 - u) * v[k].as<double>() + u * v[k + 1].as<double>();
        CHECK(std::abs(interpolated - value(j)) <= bound);
      }
    }
  }
}

}  // namespace gaitopt::test
