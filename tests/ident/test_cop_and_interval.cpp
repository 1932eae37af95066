// The measured centres of pressure in synth and diagnose, the compliant ground outside the
// library, and the held-out gain with an interval from every step left out in turn.
#include <catch2/catch.hpp>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "gaitopt/ident/cop_radius.hpp"
#include "gaitopt/ident/diagnose.hpp"
#include "gaitopt/ident/leave_one_step_out.hpp"
#include "gaitopt/ident/synth.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/diagnosis_file.hpp"
#include "gaitopt/io/measured_data.hpp"
#include "test_files.hpp"
#include "test_ident_support.hpp"
#include "test_support.hpp"

using namespace gaitopt;
using Catch::Matchers::Contains;

namespace {

const GaitFile& gait() { return test::defaultStepGait(); }

MeasuredData synth(const std::vector<Effect>& effects, const std::vector<UnmodelledEffect>& unmodelled,
                   std::uint64_t seed, int steps, bool noise = true) {
  return test::synthDefaultStep(effects, unmodelled, seed, steps, noise);
}

// Single-support runs of `d`, as [begin, end) index pairs.
std::vector<std::pair<std::size_t, std::size_t>> stances(const MeasuredData& d) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t i = 0; i < d.size();) {
    std::size_t k = i;
    while (k < d.size() && d.phase[k] == d.phase[i] && d.step[k] == d.step[i]) ++k;
    if (d.phase[i] == Phase::SingleSupport) out.push_back({i, k});
    i = k;
  }
  return out;
}

}  // namespace

TEST_CASE("synth: a compliant ground adds the sinking foot's inertia to the stance reaction",
          "[ident][synth]") {
  const double k = 5000.0;
  const MeasuredData base = synth({}, {}, 7, 4, false);
  const MeasuredData d = synth({}, {{UnmodelledKind::GroundCompliance, kNoJoint, k}}, 7, 4, false);
  REQUIRE(d.size() == base.size());
  const double mass = buildModel(gait().robot, gait().model_options).total_mass;
  const double h = d.t[1] - d.t[0];
  double worst = 0.0, scale = 0.0, torque = 0.0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    CHECK(d.q[i] == base.q[i]);
    CHECK(d.reactions[i](0) == Approx(base.reactions[i](0)).margin(1e-9));
    if (d.phase[i] == Phase::DoubleSupport) CHECK(d.reactions[i] == base.reactions[i]);
  }
  for (const auto& [b, e] : stances(d))
    for (std::size_t i = b + 2; i + 2 < e; ++i) {
      // R1z changes by −M s̈, s = R1z/K: here s̈ by the five-point stencil, not the code's three.
      const auto z = [&](std::size_t j) { return base.reactions[j](1); };
      const double zdd = (-z(i + 2) + 16 * z(i + 1) - 30 * z(i) + 16 * z(i - 1) - z(i - 2)) / (12 * h * h);
      const double expected = -mass * zdd / k;
      worst = std::max(worst, std::abs(d.reactions[i](1) - base.reactions[i](1) - expected));
      scale = std::max(scale, std::abs(expected));
      torque = std::max(torque, (d.gamma[i] - base.gamma[i]).cwiseAbs().maxCoeff());
    }
  INFO("largest R1z change " << scale << " N, worst deviation " << worst << " N");
  CHECK(scale > 20.0);  // 5000 N/m is soft ground: tens of newtons
  CHECK(worst < 0.05 * scale);
  CHECK(torque > 0.1);  // the ankle's acceleration loads the joints too
  const UnmodelledEffect spec = parseUnmodelledSpec("ground_compliance=4500");
  CHECK(spec.kind == UnmodelledKind::GroundCompliance);
  CHECK(spec.joint == kNoJoint);
  CHECK(spec.value == 4500.0);
  CHECK_THROWS_WITH(parseUnmodelledSpec("ground_compliance@knee_left=4500"), Contains("takes no joint"));
  CHECK_THROWS_WITH(parseUnmodelledSpec("ground_compliance=-1"), Contains("must be > 0"));
}

TEST_CASE("synth: centres of pressure of point and rocker feet and their radius", "[ident][synth][cop]") {
  SECTION("point foot: leg 1's centre of pressure stands still through each step") {
    const MeasuredData d = synth({}, {}, 3, 4, false);
    REQUIRE(d.has_cop);
    for (std::size_t i = 1; i < d.size(); ++i)
      if (d.step[i] == d.step[i - 1]) CHECK(d.cop[i][0] == Approx(d.cop[i - 1][0]).margin(1e-12));
    // The next step's leg 1 lands ahead: the robot walks forward.
    CHECK(d.cop.back()[0] > d.cop.front()[0] + 0.5);
  }
  SECTION("rocker: the contact rolls back by r per radian of α; copRadius recovers r") {
    const double r = 0.06;
    const MeasuredData d = synth({{EffectKind::RockerFoot, kNoJoint, r}}, {}, 3, 8);
    const PreparedData p(d);
    const CopRadius c = copRadius(p, gait().robot, gait().model_options, std::vector<char>(d.size(), 1));
    INFO("radius " << c.radius << " ± " << c.stderr_);
    CHECK(c.radius == Approx(r).epsilon(0.03));
    CHECK(std::abs(c.radius - r) < 4.0 * c.stderr_ + 1e-4);
    const MeasuredData point = synth({}, {}, 3, 8);
    const CopRadius c0 = copRadius(PreparedData(point), gait().robot, gait().model_options,
                                   std::vector<char>(point.size(), 1));
    CHECK(std::abs(c0.radius) < 4.0 * c0.stderr_ + 1e-3);
  }
}

TEST_CASE("measured-data CSV: the centres of pressure round-trip and need the reactions",
          "[io][cop]") {
  static test::ScratchDir scratch("measured_cop", "data");
  const MeasuredData d = synth({}, {}, 3, 3);
  const std::string path = scratch.fresh("cop") + ".csv";
  std::ofstream(path) << measuredCsv(d);
  const MeasuredData again = readMeasuredCsv(path);
  REQUIRE(again.has_cop);
  REQUIRE(again.cop.size() == d.size());
  CHECK(again.cop[17][0] == d.cop[17][0]);
  CHECK(again.cop[17][1] == d.cop[17][1]);
  MeasuredData no_reactions = d;
  no_reactions.has_reactions = false;
  const std::string bad = scratch.fresh("bad") + ".csv";
  std::ofstream(bad) << measuredCsv(no_reactions);
  CHECK_THROWS_WITH(readMeasuredCsv(bad), Contains("column 'cop1x'") && Contains("need the reaction columns"));
}

TEST_CASE("diagnose uses the centres of pressure, a compliant ground is not explained",
          "[ident][diagnose][cop]") {
  SECTION("rocker: the fitted radius agrees with the centres of pressure") {
    const MeasuredData d = synth({{EffectKind::RockerFoot, kNoJoint, 0.05}}, {}, 5, 20);
    const Diagnosis dg = diagnose(gait().robot, gait().model_options, d);
    REQUIRE(dg.causes.size() == 1);
    CHECK(dg.causes[0].effect.kind == EffectKind::RockerFoot);
    CHECK(dg.cop.used);
    CHECK(dg.cop.fit_is_cause);
    CHECK(dg.cop.radius_cop == Approx(0.05).epsilon(0.05));
    CHECK(std::abs(dg.cop.difference_pct) < 15.0);
    const YAML::Node j = YAML::Load(diagnosisJson(dg));
    CHECK(j["centre_of_pressure"]["used"].as<bool>());
    CHECK(j["centre_of_pressure"]["radius_fit"].as<double>() == Approx(dg.cop.radius_fit));
    CHECK_THAT(diagnosisReport(dg), Contains("The measured centres of pressure are used"));
  }
  SECTION("ground compliance: no cause, the stance reaction flagged") {
    const MeasuredData d = synth({}, {{UnmodelledKind::GroundCompliance, kNoJoint, 5000.0}}, 6, 12);
    const Diagnosis dg = diagnose(gait().robot, gait().model_options, d);
    CHECK(dg.causes.empty());
    bool r1z = false;
    for (const Unexplained& u : dg.unexplained) r1z = r1z || u.channel == kR1z;
    CHECK(r1z);
  }
}

TEST_CASE("the held-out gain has an interval from every step left out: no cause when it includes zero",
          "[ident][diagnose][interval]") {
  SECTION("a clear cause: the interval excludes zero and holds the gain") {
    const MeasuredData d = synth({{EffectKind::Coulomb, 3, 3.0}}, {}, 2, 12);
    const Diagnosis dg = diagnose(gait().robot, gait().model_options, d);
    REQUIRE(dg.causes.size() == 1);
    const GainInterval& g = dg.causes[0].step_gain;
    CHECK(g.steps == 12);
    CHECK(g.decided());
    CHECK(g.low_pct <= g.pct);
    CHECK(g.pct <= g.high_pct);
    CHECK(dg.step_gain.pct == Approx(g.pct));  // one cause: the same model against the nominal one
    const YAML::Node j = YAML::Load(diagnosisJson(dg));
    CHECK(j["cause"][0]["heldout_gain"]["low_pct"].as<double>() == Approx(g.low_pct));
    CHECK(j["gain"]["leave_one_step_out"]["steps"].as<int>() == 12);
  }
  SECTION("left-out steps: an effect the data carry is decided, one they do not is not") {
    using namespace diagnosis;
    const auto interval = [&](const MeasuredData& d, double value) {
      const PreparedData p(d);
      const std::vector<char> all(d.size(), 1), none(d.size(), 0);
      std::vector<char> fit = all, held = none;
      for (std::size_t i = 0; i < d.size(); ++i) held[i] = d.step[i] % 3 == 2, fit[i] = !held[i];
      const ResidualMatrix r0 = residuals(p, gait().robot, gait().model_options, all);
      const Problem pf{p, gait().robot, gait().model_options, fit, fitEntries(p, r0, fit, 0.03)};
      const Problem ph{p, gait().robot, gait().model_options, held, fitEntries(p, r0, held, 0.03)};
      const Context ctx{pf, ph};
      const Evaluation nominal = ctx.evaluate(gait().robot);
      const std::vector<Effect> effects = {{EffectKind::TorqueOffset, 1, value}};
      const Fit model{effects, ctx.evaluate(effects), {}};
      const LeaveOneStepOut loso(ctx, model, channelSigma(pf, r0));
      return loso.gain(nominal, {kGammaHipLeft});
    };
    const GainInterval real = interval(synth({{EffectKind::TorqueOffset, 1, 1.0}}, {}, 4, 6), 1.0);
    INFO("real: " << real.pct << " % [" << real.low_pct << ", " << real.high_pct << "]");
    CHECK(real.steps == 6);
    CHECK(real.decided());
    // On data without the offset, the refits without each step pull the value back to ~0: the
    // left-out predictions are no better than the nominal model's, whatever value was fitted.
    const GainInterval none = interval(synth({}, {}, 4, 6), 0.2);
    INFO("none: " << none.pct << " % [" << none.low_pct << ", " << none.high_pct << "]");
    CHECK_FALSE(none.decided());
    CHECK(none.low_pct <= 0.0);
  }
}
