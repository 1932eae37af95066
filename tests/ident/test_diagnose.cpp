// gaitopt diagnose on hidden effects: one seeded case per effect at 20 steps, null
// data, two effects at once, a confounded pair, and invariance to column order and to a
// consistent swap of the stance labels, the `inertial` last resort. The >= 100-case hit rate is
// bench/bench_diagnose_hitrate.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "gaitopt/ident/diagnose.hpp"
#include "gaitopt/io/diagnosis_file.hpp"
#include "gaitopt/ident/synth.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "test_ident_support.hpp"
#include "test_support.hpp"

using namespace gaitopt;

namespace {

const GaitFile& gait() { return test::defaultStepGait(); }

MeasuredData synth(const std::vector<Effect>& effects, std::uint64_t seed, int steps = 20) {
  SynthOptions o;
  o.steps = steps;
  o.seed = seed;
  return synthesize(gait().robot, gait().parameters, gait().options, gait().model_options, effects, o);
}

double deviation(const Effect& e) { return effectInfo(e.kind).factor ? e.value - 1.0 : e.value; }

// The data a diagnosis of `truth` is tested on: with centres of pressure the foot moment is
// measured, so a foot_offset's moment is no model error and the offset reaches the dynamics
// only through the ankle's motion, too weakly at these magnitudes; it is diagnosed from the
// foot moment the dynamics need, i.e. on the data without their centres of pressure.
MeasuredData forDiagnosis(MeasuredData d, const Effect& truth) {
  if (truth.kind == EffectKind::FootOffset) d.has_cop = false;
  return d;
}

void requireFound(const Diagnosis& d, const Effect& truth) {
  INFO("truth " << effectLabel(truth) << " = " << truth.value);
  REQUIRE(!d.causes.empty());
  const Cause& c = d.causes[0];
  INFO("found " << effectLabel(c.effect) << " = " << c.effect.value << " +- " << c.stderr_);
  CHECK(effectLabel(c.effect) == effectLabel(truth));
  CHECK(std::abs(deviation(c.effect) - deviation(truth)) <= 0.1 * std::abs(deviation(truth)));
  // The held-out gain, on the channels the cause acts on (Diagnosis::effect_channels).
  INFO("effect channels gain " << d.effect_channels_pct << " %, overall " << d.overall_pct << " %");
  CHECK(d.effect_channels_pct > 50.0);
  CHECK(!d.inertial.accepted);  // a named effect explains the data: no inertial fall-back
}

}  // namespace

TEST_CASE("diagnose names each hidden effect, its joint and value", "[ident][diagnose]") {
  for (int k = 0; k < kNumEffectKinds; ++k) {
    if (static_cast<EffectKind>(k) == EffectKind::Inertial) continue;  // its own test below
    std::mt19937_64 rng(1000 + k);
    const Effect truth = randomEffect(static_cast<EffectKind>(k), rng);
    SECTION(effectInfo(truth.kind).name) {
      requireFound(diagnose(gait().robot, gait().model_options, forDiagnosis(synth({truth}, 50 + k), truth)),
                   truth);
    }
  }
}

TEST_CASE("diagnose reports no cause on data of the nominal model", "[ident][diagnose]") {
  for (std::uint64_t seed : {101u, 102u}) {
    const Diagnosis d = diagnose(gait().robot, gait().model_options, synth({}, seed));
    INFO("seed " << seed << ": " << (d.causes.empty() ? "" : effectLabel(d.causes[0].effect)));
    CHECK(d.causes.empty());
    CHECK(d.unexplained.empty());
    CHECK(d.extended.normalised_rms == Approx(d.nominal.normalised_rms));
  }
}

TEST_CASE("diagnose names each hidden effect on 12 noisier steps at the low end of its range",
          "[ident][diagnose]") {
  // The short profile of the hidden-effect suite: 12 steps, every noise x1.5, magnitudes in the
  // lowest quarter of randomEffect's ranges.
  for (int k = 0; k < kNumEffectKinds; ++k) {
    if (static_cast<EffectKind>(k) == EffectKind::Inertial) continue;
    std::mt19937_64 rng(2000 + k);
    const Effect truth = randomEffect(static_cast<EffectKind>(k), rng, true);
    SECTION(effectInfo(truth.kind).name) {
      SynthOptions o;
      o.steps = 12;
      o.seed = 60 + k;
      o.torque_noise *= 1.5;
      o.force_noise *= 1.5;
      o.encoder_counts = static_cast<int>(o.encoder_counts / 1.5);
      const Diagnosis d = diagnose(gait().robot, gait().model_options,
                                   forDiagnosis(synthesize(gait().robot, gait().parameters, gait().options,
                                                           gait().model_options, {truth}, o),
                                                truth));
      INFO("truth " << effectLabel(truth) << " = " << truth.value);
      REQUIRE(d.causes.size() == 1);
      INFO("found " << effectLabel(d.causes[0].effect) << " = " << d.causes[0].effect.value);
      CHECK(effectLabel(d.causes[0].effect) == effectLabel(truth));
      CHECK(std::abs(deviation(d.causes[0].effect) - deviation(truth)) <= 0.15 * std::abs(deviation(truth)));
      CHECK(d.unexplained.empty());
    }
  }
}

TEST_CASE("diagnose names no encoder offset below the angle resolution beside a backlash",
          "[ident][diagnose]") {
  // The fitted backlash's tanh of the noisy torque is biased; the fraction of an encoder count
  // that leaves looked like a second cause.
  const Diagnosis d = diagnose(gait().robot, gait().model_options,
                               synth({{EffectKind::Backlash, 0, 0.015}}, 7, 12));
  REQUIRE(d.causes.size() == 1);
  CHECK(effectLabel(d.causes[0].effect) == "backlash@knee_left");
  for (const PartialFit& f : d.partial_fits)
    if (f.effect.kind == EffectKind::EncoderOffset) CHECK_THAT(f.reason, Catch::Contains("below the angle resolution"));
}

TEST_CASE("diagnose finds two effects at once", "[ident][diagnose]") {
  const Effect a{EffectKind::Coulomb, 2, 4.0}, b{EffectKind::Payload, kNoJoint, 3.0};
  const Diagnosis d = diagnose(gait().robot, gait().model_options, synth({a, b}, 7));
  std::vector<std::string> found;
  for (const Cause& c : d.causes) found.push_back(effectLabel(c.effect));
  CHECK(std::count(found.begin(), found.end(), effectLabel(a)) == 1);
  CHECK(std::count(found.begin(), found.end(), effectLabel(b)) == 1);
  CHECK(d.overall_pct > 50.0);
}

TEST_CASE("diagnose reports a confounded pair as one class", "[ident][diagnose]") {
  // Only the single-support runs where knee_right turns forward (each run its own "step"): a
  // Coulomb torque and a torque offset on that joint are then indistinguishable.
  const MeasuredData full = synth({{EffectKind::TorqueOffset, 3, 3.0}}, 11);
  MeasuredData d = full;
  d.t.clear(); d.q.clear(); d.phase.clear(); d.stance.clear(); d.step.clear();
  d.gamma.clear(); d.reactions.clear();
  long run = -1;
  std::vector<std::size_t> rows;
  const auto flush = [&] {
    if (rows.size() >= 40) {
      ++run;
      for (std::size_t i : rows) {
        d.t.push_back(full.t[i]); d.q.push_back(full.q[i]); d.phase.push_back(full.phase[i]);
        d.stance.push_back(full.stance[i]); d.step.push_back(run);
        d.gamma.push_back(full.gamma[i]); d.reactions.push_back(full.reactions[i]);
      }
    }
    rows.clear();
  };
  for (std::size_t i = 0; i + 1 < full.size(); ++i) {
    const int motor = full.stance[i] == Stance::Left ? 3 : 0;  // knee_right
    const bool same = full.step[i + 1] == full.step[i] && full.phase[i + 1] == full.phase[i];
    const bool forward = same && motorAngles(full.q[i + 1])(motor) > motorAngles(full.q[i])(motor);
    if (forward && full.phase[i] == Phase::SingleSupport) rows.push_back(i); else flush();
  }
  flush();
  REQUIRE(run >= 5);
  DiagnoseOptions o;
  o.kinds = {EffectKind::Coulomb, EffectKind::TorqueOffset};
  const Diagnosis dg = diagnose(gait().robot, gait().model_options, d, o);
  REQUIRE(dg.causes.size() == 1);
  const Cause& c = dg.causes[0];
  std::vector<std::string> cls = c.confounded_with;
  cls.push_back(effectLabel(c.effect));
  std::sort(cls.begin(), cls.end());
  CHECK(cls == std::vector<std::string>{"coulomb@knee_right", "torque_offset@knee_right"});
  CHECK(c.effect.value == Approx(3.0).epsilon(0.1));
}

TEST_CASE("diagnose is invariant to a consistent swap of the stance labels", "[ident][diagnose]") {
  const Effect truth{EffectKind::Viscous, 1, 3.0};  // hip_left
  MeasuredData d = synth({truth}, 21, 12);
  const Diagnosis a = diagnose(gait().robot, gait().model_options, d);
  for (Stance& s : d.stance) s = s == Stance::Left ? Stance::Right : Stance::Left;
  const Diagnosis b = diagnose(gait().robot, gait().model_options, d);
  REQUIRE(a.causes.size() == b.causes.size());
  REQUIRE(!a.causes.empty());
  CHECK(effectLabel(a.causes[0].effect) == "viscous@hip_left");
  CHECK(effectLabel(b.causes[0].effect) == "viscous@hip_right");  // the mirrored joint
  CHECK(b.causes[0].effect.value == Approx(a.causes[0].effect.value).epsilon(1e-9));
}

TEST_CASE("diagnose falls back to the inertial parameters when no named effect explains the data",
          "[ident][diagnose][inertial]") {
  // A trunk inertia 40 % above the robot file's: no named effect changes J_trunk alone.
  RobotParams truth = gait().robot;
  truth.inertia[2] *= 1.4;
  SynthOptions so;
  so.seed = 5;
  const MeasuredData data = synthesize(truth, gait().parameters, gait().options,
                                       gait().model_options, {}, so);
  const Diagnosis d = diagnose(gait().robot, gait().model_options, data);
  REQUIRE(d.causes.size() == 1);
  CHECK(d.causes[0].effect.kind == EffectKind::Inertial);
  CHECK(d.causes[0].p_value < 0.01);
  REQUIRE(d.inertial.accepted);
  CHECK(d.inertial.holdout_rms_after < 0.6 * d.inertial.holdout_rms_before);
  INFO("effect channels gain " << d.effect_channels_pct << " %");
  CHECK(d.effect_channels_pct > 50.0);
  // The trunk's inertia about the hip is a base parameter on its own: its change is found.
  const double truth_change = 0.4 * gait().robot.inertia[2];
  bool found = false;
  for (int i = 0; i < d.inertial.base.rank; ++i)
    if (d.inertial.base.label(i) == "J_trunk") {
      found = true;
      const double change = d.inertial.base_fitted(i) - d.inertial.base_nominal(i);
      INFO("J_trunk change " << change << " +- " << d.inertial.base_stderr(i));
      CHECK(std::abs(change - truth_change) < 0.1 * truth_change);
      CHECK(d.inertial.base_stderr(i) < 0.05 * truth_change);
    }
  CHECK(found);
  // Physically consistent, and what extended_robot.yaml carries.
  const RobotParams& e = d.extended_robot;
  for (int i = 0; i < 5; ++i) {
    CHECK(e.mass[i] > 0.0);
    CHECK(e.inertia[i] > 0.0);
    CHECK(e.s[i] > 0.0);
  }
  CHECK(e.inertia[2] == Approx(truth.inertia[2]).epsilon(0.1));
  const std::string path = test::sourcePath("configs/robot/rabbit_miossec.yaml");
  const RobotParams written = parseRobot(YAML::Load(extendedRobotYaml(path, e)), "extended");
  for (int i = 0; i < 5; ++i) {
    CHECK(written.mass[i] == e.mass[i]);
    CHECK(written.s[i] == e.s[i]);
    CHECK(written.inertia[i] == e.inertia[i]);
  }
}
