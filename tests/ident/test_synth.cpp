// gaitopt synth: the TRUE model's data are consistent with the TRUE model's equations.
#include <catch2/catch.hpp>

#include <cmath>

#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/ident/residual_model.hpp"
#include "gaitopt/ident/synth.hpp"
#include "gaitopt/io/gait_file.hpp"
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
    const PreparedData p(d);
    const GaitFile g = defaultGait();
    const std::vector<char> all(d.size(), 1);
    const ResidualMatrix r = residuals(p, withEffects(g.robot, effects), g.model_options, all);
    INFO("effects " << effects.size());
    for (int c = 0; c < kNumChannels; ++c) INFO(kChannelNames[c] << " " << channelRms(r, c));
    CHECK(channelRms(r, kAlphaRow) < 0.05);
    for (int c = kGammaKneeLeft; c <= kGammaKneeRight; ++c) CHECK(channelRms(r, c) < 0.05);
    for (int c = kR1x; c <= kR2z; ++c) CHECK(channelRms(r, c) < 0.1);
    CHECK(channelRms(r, kFoot2z) < 1e-5);
  }
}
