// bench_impact: wall-clock cost of one rigid impact on the default robot
// (configs/robot/rabbit_miossec.yaml): the algebraic solve (12 behaviours enumerated) and the
// differential solve (phases in τ), each including the floating-model terms A, D1, D2 and
// W = D A⁻¹ Dᵀ; plus one behaviour of the templated core on a forward AD scalar (values and
// the 14 derivatives with respect to X and Ẋ⁻), what a gradient-based optimiser calls.
//
//   bench_impact [--json FILE] [--batch N] [--repeats N] [--help]
//
// Cases cycle through 2 double-support configurations (walking-like and legs-spread, see the
// docs/commands/impact.md) × 36 arrival directions θ ∈ (−180°, 0°) × μ ∈ {0.3, 0.7, 1.2}. Targets: median
// ≤ 20 µs per algebraic and per differential solve.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <vector>

#include "bench_timing.hpp"
#include "gaitopt/gait/leg_geometry.hpp"
#include "gaitopt/impact/impact_map.hpp"
#include "gaitopt/impact/solve_impact.hpp"
#include "gaitopt/io/robot_file.hpp"

namespace {

using namespace gaitopt;
using namespace gaitopt::bench;

constexpr const char* kRobotFile = GAITOPT_SOURCE_DIR "/configs/robot/rabbit_miossec.yaml";
constexpr double kTargetNs = 20000.0;

struct Case {
  Vector7<double> X, Xd;
  double mu;
};

Vec5 doubleSupport(const Model& m, double alpha, double delta1, double theta3, double step) {
  const Vec2 hip = -foot1FromHip(m, alpha, delta1);
  const Vec2 d34 = leg2InverseKinematics(m, alpha, delta1, Vec2(Vec2(step, 0.0) - hip));
  return Vec5(alpha, delta1, delta2FromTheta3(alpha, delta1, theta3), d34(0), d34(1));
}

std::vector<Case> makeCases(const Model& m) {
  std::vector<Case> cases;
  for (const Vec5& q : {doubleSupport(m, -0.4, -M_PI + 0.3, 0.5 * M_PI + 0.1, 0.38),
                        doubleSupport(m, -1.0, -M_PI, 0.0, 1.10)})
    for (int k = 0; k < 36; ++k)
      for (double mu : {0.3, 0.7, 1.2}) {
        const double th = -M_PI * (k + 0.5) / 36.0;
        Case c;
        c.mu = mu;
        floatingStateFromPinned(m, q, pinnedVelocityForFoot2(m, q, Vec2(std::cos(th), std::sin(th))),
                                c.X, c.Xd);
        cases.push_back(c);
      }
  return cases;
}

template <class Call>
Stats measureCases(const std::string& name, const std::string& description,
                   const std::vector<Case>& cases, int batch, int repeats, Call call) {
  std::size_t k = 0;
  return measure(name, description, batch, repeats, [&]() {
    const double r = call(cases[k]);
    if (++k == cases.size()) k = 0;
    return r;
  });
}

using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, 14, 1>>;

}  // namespace

int main(int argc, char** argv) {
  BatchOptions opts;
  if (const auto status = parseBatchOptions(argc, argv, "bench_impact", 2000, opts))
    return *status;
  Model model;
  try {
    model = buildModel(loadRobot(kRobotFile));
  } catch (const std::exception& e) {
    std::cerr << "bench_impact: error: " << e.what() << "\n";
    return 2;
  }
  const std::vector<Case> cases = makeCases(model);
  const Environment env;
  printEnvironment("bench_impact", env);
  std::printf("cases:     %zu (2 configurations x 36 directions x 3 friction values), cycled\n",
              cases.size());
  std::printf("timing:    %d batches of %d calls (+1 warm-up batch)\n\n", opts.repeats, opts.batch);

  const auto solve = [&model](ImpactModelKind kind) {
    return [&model, kind](const Case& c) {
      ImpactOptions o;
      o.mu = c.mu;
      const ImpactResult r = solveImpact(model, c.X, c.Xd, kind, o);
      escape(r);
      return r.solutions.empty() ? 0.0 : r.solutions.front().energy_loss;
    };
  };
  std::vector<Stats> results;
  results.push_back(measureCases("algebraic", "A, D, W + 12 behaviours, all consistent ones kept",
                                 cases, opts.batch, opts.repeats, solve(ImpactModelKind::Algebraic)));
  results.push_back(measureCases("differential", "A, D, W + phase sequence in tau",
                                 cases, opts.batch, opts.repeats,
                                 solve(ImpactModelKind::Differential)));
  results.push_back(measureCases(
      "algebraicCoreAD", "one behaviour (lift/stick) on AD, 14 directions (X, Xd-)", cases,
      opts.batch / 4 + 1, opts.repeats, [&model](const Case& c) {
        Vector7<AD> X, Xd;
        for (int i = 0; i < 7; ++i) {
          X(i) = AD(c.X(i), 14, i);
          Xd(i) = AD(c.Xd(i), 14, 7 + i);
        }
        const ImpactOutcome<AD> o = algebraicImpact(
            model, X, Xd, ImpactBehaviour{Foot1Behaviour::Lift, Foot2Behaviour::Stick}, c.mu);
        escape(o);
        return o.Xd_plus(0).derivatives()(3);
      }));

  std::printf("%-20s %12s %12s %12s  %s\n", "measurement (ns)", "median", "min", "p90", "target");
  for (const Stats& s : results) {
    const bool targeted = s.name != "algebraicCoreAD";
    std::printf("%-20s %12.1f %12.1f %12.1f  %s\n", s.name.c_str(), s.median_ns, s.min_ns,
                s.p90_ns, targeted ? verdict(s.median_ns, kTargetNs) : "-");
  }
  std::printf("\n(sink %g)\n", static_cast<double>(g_sink));
  if (!opts.json_path.empty()) {
    JsonWriter w;
    w.beginObject();
    writeEnvironment(w, "bench_impact", env);
    w.key("cases").value(static_cast<int>(cases.size()));
    w.key("batch").value(opts.batch);
    w.key("repeats").value(opts.repeats);
    w.key("target_ns").value(kTargetNs);
    writeResultsArray(w, results);
    w.endObject();
    if (!writeJsonReport("bench_impact", opts.json_path, w)) return 1;
  }
  return 0;
}
