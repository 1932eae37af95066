// bench_model: wall-clock cost of one evaluation of the dynamic model and of its exact first
// derivatives, on the default robot (configs/robot/rabbit_miossec.yaml).
//
//   bench_model [--json FILE] [--batch N] [--repeats N] [--help]
//
// Each measurement times `batch` consecutive calls (default 10000) cycling through 1000
// pre-generated, seeded, walking-like random states, and repeats that `repeats` times (default
// 51, at least 31 recommended) after one untimed warm-up batch. Reported per call, in ns: the
// median, the minimum and the 90th percentile over the repeated batches.
//
// Dead-code elimination is prevented twice: every result object escapes through an empty asm
// statement with a memory clobber (so all of its fields must be computed), and one entry of it
// per call is accumulated into a volatile sink.
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"
#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/model/derivatives.hpp"
#include "gaitopt/io/robot_file.hpp"

namespace {

using namespace gaitopt;
using namespace gaitopt::bench;

constexpr const char* kRobotFile = GAITOPT_SOURCE_DIR "/configs/robot/rabbit_miossec.yaml";
constexpr std::size_t kStateCount = 1000;
constexpr unsigned kSeed = 20040611;
constexpr SignMode kSignMode = SignMode::Smooth;  // the variant used in optimisation

struct State {
  Vec5 q, qd, qdd;
};

// Walking-like states: knees flexed, trunk near upright, moderate speeds and accelerations.
std::vector<State> makeStates(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<State> states(n);
  for (State& s : states) {
    s.q << 0.4 * u(rng), -M_PI + 0.3 + 0.2 * u(rng), -M_PI + 0.4 * u(rng), 0.6 * u(rng),
        -M_PI + 0.3 + 0.2 * u(rng);
    for (int i = 0; i < 5; ++i) s.qd(i) = 2.0 * u(rng);
    for (int i = 0; i < 5; ++i) s.qdd(i) = 10.0 * u(rng);
  }
  return states;
}

// Per-call times of `call` cycling through the pre-generated states (see bench_timing.hpp).
Stats measureOnStates(const std::string& name, const std::string& description,
                      const std::vector<State>& states, int batch, int repeats,
                      double (*call)(const Model&, const State&), const Model& model) {
  std::size_t k = 0;
  return measure(name, description, batch, repeats, [&]() {
    const double r = call(model, states[k]);
    if (++k == states.size()) k = 0;
    return r;
  });
}

// The four measured calls. Each returns one entry of its result for the sink.
double callPinnedTerms(const Model& m, const State& s) {
  const PinnedTerms<double> t = pinnedTerms(m, s.q, s.qd);
  escape(t);
  return t.A(0, 1) + t.C(2) + t.G(0) + t.D2(1, 3) + t.H2(0);
}

double callPinnedTermsDerivatives(const Model& m, const State& s) {
  const PinnedDerivatives d = pinnedTermsDerivatives(m, s.q, s.qd);
  escape(d);
  return d.value.A(0, 1) + d.dA_dq[2](0, 1) + d.dC_dqd(1, 3) + d.dH2_dq(1, 2);
}

double callInverseDynamics(const Model& m, const State& s) {
  const SingleSupportInverseDynamics<double> r = inverseDynamicsSS(m, s.q, s.qd, s.qdd, kSignMode);
  escape(r);
  return r.gamma_star(1) + r.alpha_row_residual + r.R1(1);
}

double callInverseDynamicsDerivatives(const Model& m, const State& s) {
  const InverseDynamicsSSDerivatives d =
      inverseDynamicsSSDerivatives(m, s.q, s.qd, s.qdd, kSignMode);
  escape(d);
  return d.value.gamma_star(1) + d.dgamma_star(2, 7) + d.dR1(1, 11);
}

}  // namespace

int main(int argc, char** argv) {
  BatchOptions opts;
  if (const auto status = parseBatchOptions(argc, argv, "bench_model", 10000, opts))
    return *status;
  const int batch = opts.batch, repeats = opts.repeats;

  Model model;
  try {
    model = buildModel(loadRobot(kRobotFile));
  } catch (const std::exception& e) {
    std::cerr << "bench_model: error: " << e.what() << "\n";
    return 2;
  }
  const std::vector<State> states = makeStates(kStateCount, kSeed);
  const Environment env;

  printEnvironment("bench_model", env);
  std::printf("robot:     %s\n", kRobotFile);
  std::printf("states:    %zu seeded random states (seed %u), cycled\n", states.size(), kSeed);
  std::printf("timing:    %d batches of %d calls (+1 warm-up batch), steady_clock\n", repeats,
              batch);
  std::printf("friction:  smooth sign tanh(w/eps), eps = %g rad/s\n\n",
              model.options.friction_smoothing);

  std::vector<Stats> results;
  results.push_back(measureOnStates("pinnedTerms", "A, C, G, D2, H2 (pinned model), double",
                                    states, batch, repeats, callPinnedTerms, model));
  results.push_back(measureOnStates("pinnedTermsDerivatives",
                                    "values + d/dq, d/dqd (forward AD, 10 directions)", states,
                                    batch, repeats, callPinnedTermsDerivatives, model));
  results.push_back(measureOnStates("inverseDynamicsSS",
                                    "Gamma*, Gamma, alpha residual, R1, double", states, batch,
                                    repeats, callInverseDynamics, model));
  results.push_back(measureOnStates("inverseDynamicsSSDerivatives",
                                    "values + d/d(q, qd, qdd) (forward AD, 15 directions)", states,
                                    batch, repeats, callInverseDynamicsDerivatives, model));

  std::printf("%-30s %12s %12s %12s\n", "measurement (ns per call)", "median", "min", "p90");
  std::printf("%-30s %12s %12s %12s\n", "------------------------------", "------------",
              "------------", "------------");
  for (const Stats& s : results) {
    std::printf("%-30s %12.1f %12.1f %12.1f\n", s.name.c_str(), s.median_ns, s.min_ns, s.p90_ns);
  }
  std::printf("\n(sink %g)\n", static_cast<double>(g_sink));

  if (!opts.json_path.empty()) {
    JsonWriter w;
    w.beginObject();
    writeEnvironment(w, "bench_model", env);
    w.key("robot").value(std::string(kRobotFile));
    w.key("states").value(static_cast<int>(states.size()));
    w.key("seed").value(static_cast<int>(kSeed));
    w.key("batch").value(batch);
    w.key("repeats").value(repeats);
    w.key("friction_sign").value("smooth");
    w.key("unit").value("ns per call");
    writeResultsArray(w, results);
    w.endObject();
    if (!writeJsonReport("bench_model", opts.json_path, w)) return 1;
  }
  return 0;
}
