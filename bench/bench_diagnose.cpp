// Benchmarks of `gaitopt synth` and `gaitopt diagnose` on 20 steps at 500 Hz (medians), and
// with --hit-rate N the hidden-effect acceptance of issue 9 over N seeded cases per effect plus
// 2N null cases: effect and joint named, value within 10 % (of the deviation from 1 for
// factors), best held-out channel gain > 50 %; null: no cause.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "bench_timing.hpp"
#include "gaitopt/ident/diagnose.hpp"
#include "gaitopt/ident/synth.hpp"
#include "gaitopt/io/gait_file.hpp"

using namespace gaitopt;

namespace {

MeasuredData synth(const GaitFile& g, const std::vector<Effect>& effects, std::uint64_t seed) {
  SynthOptions o;
  o.seed = seed;
  return synthesize(g.robot, g.parameters, g.options, g.model_options, effects, o);
}

double seconds(const std::function<void()>& f) {
  const auto t0 = bench::Clock::now();
  f();
  return std::chrono::duration<double>(bench::Clock::now() - t0).count();
}

void hitRate(const GaitFile& g, int n) {
  for (int k = -1; k < kNumEffectKinds; ++k) {
    int named = 0, valued = 0, gained = 0;
    double worst_error = 0.0;
    const int cases = k < 0 ? 2 * n : n;  // null: twice as many
    for (int i = 0; i < cases; ++i) {
      std::mt19937_64 rng(10000 * (k + 2) + i);
      std::vector<Effect> truth;
      if (k >= 0) truth.push_back(randomEffect(static_cast<EffectKind>(k), rng));
      const Diagnosis d = diagnose(g.robot, g.model_options, synth(g, truth, 777 + i));
      if (k < 0) {
        named += d.causes.empty();
        continue;
      }
      if (d.causes.empty() || effectLabel(d.causes[0].effect) != effectLabel(truth[0])) continue;
      ++named;
      const bool f = effectInfo(truth[0].kind).factor;
      const double err = std::abs((d.causes[0].effect.value - truth[0].value) /
                                  (f ? truth[0].value - 1.0 : truth[0].value));
      worst_error = std::max(worst_error, err);
      valued += err <= 0.1;
      double best = -1e300;
      for (double x : d.rms_reduction_pct)
        if (std::isfinite(x)) best = std::max(best, x);
      gained += best > 50.0;
    }
    std::printf("%-15s named %3d/%d  value<=10%% %3d  gain>50%% %3d  worst value error %.1f%%\n",
                k < 0 ? "null (no cause)" : effectInfo(static_cast<EffectKind>(k)).name, named, cases,
                valued, gained, 100.0 * worst_error);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const GaitFile g = loadGaitFile(std::string(GAITOPT_SOURCE_DIR) + "/configs/gait/default_step.yaml");
  if (argc == 3 && std::strcmp(argv[1], "--hit-rate") == 0) {
    hitRate(g, std::atoi(argv[2]));
    return 0;
  }
  const Effect effect{EffectKind::Coulomb, 3, 3.2};
  std::vector<double> ts, td;
  for (int rep = 0; rep < 5; ++rep) {
    MeasuredData d;
    ts.push_back(seconds([&] { d = synth(g, {effect}, rep + 1); }));
    td.push_back(seconds([&] { bench::g_sink = bench::g_sink + diagnose(g.robot, g.model_options, d).overall_pct; }));
  }
  std::printf("synth 20 steps: median %.3f s (min %.3f)\ndiagnose 20 steps at 500 Hz: median %.3f s (min %.3f)\n",
              bench::sampleStats(ts).median, bench::sampleStats(ts).min,
              bench::sampleStats(td).median, bench::sampleStats(td).min);
  return 0;
}
