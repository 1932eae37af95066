// Benchmarks of `gaitopt synth` and `gaitopt diagnose` on 20 steps at 500 Hz (medians). The
// hidden-effect acceptance is bench_diagnose_hitrate.cpp.
#include <cstdio>

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

}  // namespace

int main() {
  const GaitFile g = loadGaitFile(std::string(GAITOPT_SOURCE_DIR) + "/configs/gait/default_step.yaml");
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
