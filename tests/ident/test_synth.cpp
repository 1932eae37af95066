// gaitopt synth: the TRUE model's data are consistent with the TRUE model's equations.
#include <catch2/catch.hpp>

#include <cmath>

#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/ident/residual_model.hpp"
#include "gaitopt/ident/synth.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/measured_data.hpp"
#include "test_ident_support.hpp"
#include "test_support.hpp"

using namespace gaitopt;

namespace {

GaitFile defaultGait() { return loadGaitFile(test::sourcePath("configs/gait/default_step.yaml")); }

MeasuredData synth(const std::vector<Effect>& effects, bool noise, int steps = 4,
                   std::uint64_t seed = 7) {
  const GaitFile g = defaultGait();
  SynthOptions o;
  o.steps = steps;
  o.noise = noise;
  o.seed = seed;
  return synthesize(g.robot, g.parameters, g.options, g.model_options, effects, o);
}

double channelRms(const ResidualMatrix& r, int c) {
  double s = 0.0;
  int n = 0;
  for (Eigen::Index i = 0; i < r.rows(); ++i)
    if (std::isfinite(r(i, c))) {
      s += r(i, c) * r(i, c);
      ++n;
    }
  return n ? std::sqrt(s / n) : 0.0;
}

}  // namespace

TEST_CASE("synth without noise: residuals of the TRUE model vanish", "[ident]") {
  for (const auto& effects : std::vector<std::vector<Effect>>{
           {}, {{EffectKind::Slope, kNoJoint, 0.03}}, {{EffectKind::Payload, kNoJoint, 5.0}}}) {
    const MeasuredData d = synth(effects, false);
    const PreparedData p(d, test::exactSmoothing());
    const GaitFile g = defaultGait();
    // Single support away from the phase ends (the smoothing differentiator is one-sided
    // there), double support whole (only its closure residual is checked).
    std::vector<char> rows(d.size(), 0);
    for (const Segment& s : p.segments)
      for (std::size_t i = s.begin; i < s.end; ++i)
        rows[i] = s.phase == Phase::DoubleSupport ||
                  (d.t[i] - d.t[s.begin] >= 0.03 && d.t[s.end - 1] - d.t[i] >= 0.03);
    ResidualMatrix r = residuals(p, withEffects(g.robot, effects), g.model_options, rows);
    for (const Segment& s : p.segments)
      if (s.phase == Phase::DoubleSupport) r.block(s.begin, 0, s.end - s.begin, kFoot2z).setConstant(NAN);
    INFO("effects " << effects.size());
    std::string rms;
    for (int c = 0; c < kNumChannels; ++c) rms += std::string(kChannelNames[c]) + " " + std::to_string(channelRms(r, c)) + "; ";
    INFO(rms);
    CHECK(channelRms(r, kAlphaRow) < 0.02);
    for (int c = kGammaKneeLeft; c <= kGammaKneeRight; ++c) CHECK(channelRms(r, c) < 0.15);
    for (int c = kR1x; c <= kR2z; ++c) CHECK(channelRms(r, c) < 0.25);
    CHECK(channelRms(r, kFoot2z) < 1e-6);
  }
}

TEST_CASE("synth: hidden effects change the data the nominal model predicts", "[ident]") {
  const GaitFile g = defaultGait();
  const MeasuredData d = synth({{EffectKind::TorqueOffset, 3, 2.0}}, false);
  const PreparedData p(d, test::exactSmoothing());
  const ResidualMatrix r = residuals(p, g.robot, g.model_options, std::vector<char>(d.size(), 1));
  // Mean single-support residual per knee: the offset on knee_right only.
  const auto ssMean = [&](int c) {
    double mean = 0.0;
    int n = 0;
    for (Eigen::Index i = 0; i < r.rows(); ++i)
      if (d.phase[i] == Phase::SingleSupport && std::isfinite(r(i, c))) {
        mean += r(i, c);
        ++n;
      }
    return mean / n;
  };
  CHECK(ssMean(kGammaKneeRight) == Approx(2.0).margin(0.2));  // measured = true + offset
  CHECK(std::abs(ssMean(kGammaKneeLeft)) < 0.2);
}

TEST_CASE("synth: seeded, reproducible, alternating stance, noise as specified", "[ident]") {
  const MeasuredData a = synth({}, true, 4, 3), b = synth({}, true, 4, 3), c = synth({}, true, 4, 4);
  CHECK(measuredCsv(a) == measuredCsv(b));
  CHECK(measuredCsv(a) != measuredCsv(c));
  for (std::size_t i = 0; i < a.size(); ++i)
    CHECK(a.stance[i] == (a.step[i] % 2 == 0 ? Stance::Left : Stance::Right));
  const double count = 2.0 * M_PI / (1 << 14);  // encoder quantisation of the motor angles
  for (std::size_t i = 0; i < a.size(); i += 37) {
    const Vec4 m = motorAngles(a.q[i]);
    for (int j = 0; j < 4; ++j) CHECK(std::abs(m(j) / count - std::round(m(j) / count)) < 1e-6);
  }
  const MeasuredData exact = synth({}, false, 4, 3);  // same motion, no noise
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += (a.gamma[i] - exact.gamma[i]).squaredNorm();
  CHECK(std::sqrt(s / (4.0 * a.size())) == Approx(0.3).epsilon(0.1));
  const double dt = a.t[1] - a.t[0];
  CHECK(dt == Approx(1.0 / 500.0));
}
