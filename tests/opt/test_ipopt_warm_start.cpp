// Ipopt warm start (warm_start_init_point with the previous solve's multipliers, as the
// optimiser does between exchange rounds and restarts): the same optimum as a cold solve, in
// fewer iterations than a restart from the same point without multipliers, for each Hessian
// mode of the adapter. Solves from concurrent threads run one at a time.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <thread>
#include <vector>

#include "gaitopt/opt/nlp_solver.hpp"

using gaitopt::MatrixX;
using gaitopt::VectorX;

namespace {

// (x0 − 2)² + (x1 − 1)² + (x2 − 0.5)² + x0 x2: strictly convex, its unconstrained minimum lies
// outside the unit disc below, so the disc is active at the optimum.
class ShiftedQuadratic : public gaitopt::CostTerm {
 public:
  std::string name() const override { return "shifted quadratic"; }
  bool value(const VectorX& x, double& f) override {
    f = std::pow(x(0) - 2, 2) + std::pow(x(1) - 1, 2) + std::pow(x(2) - 0.5, 2) + x(0) * x(2);
    return true;
  }
  bool gradient(const VectorX& x, Eigen::Ref<VectorX> g) override {
    g << 2 * (x(0) - 2) + x(2), 2 * (x(1) - 1), 2 * (x(2) - 0.5) + x(0);
    return true;
  }
};

// x0² + x1² ≤ 1 (active at the optimum) and x0 + x1 + x2 ≥ −1 (inactive).
class DiscAndPlane : public gaitopt::ConstraintSet {
 public:
  std::string name() const override { return "disc and plane"; }
  int size() const override { return 2; }
  void bounds(Eigen::Ref<VectorX> lo, Eigen::Ref<VectorX> hi) const override {
    lo << -1e20, -1.0;
    hi << 1.0, 1e20;
  }
  bool values(const VectorX& x, Eigen::Ref<VectorX> g) override {
    g << x(0) * x(0) + x(1) * x(1), x(0) + x(1) + x(2);
    return true;
  }
  bool jacobian(const VectorX& x, Eigen::Ref<MatrixX> j) override {
    j << 2 * x(0), 2 * x(1), 0.0, 1.0, 1.0, 1.0;
    return true;
  }
};

// The shifted quadratic, counting how many evaluations run at once (each lasts 200 µs).
class ConcurrencyProbe : public ShiftedQuadratic {
 public:
  ConcurrencyProbe(std::atomic<int>& inside, std::atomic<int>& most)
      : inside_(inside), most_(most) {}
  bool value(const VectorX& x, double& f) override {
    const int now = ++inside_;
    int seen = most_.load();
    while (now > seen && !most_.compare_exchange_weak(seen, now)) {
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    --inside_;
    return ShiftedQuadratic::value(x, f);
  }

 private:
  std::atomic<int>& inside_;
  std::atomic<int>& most_;
};

gaitopt::VariableSet boxFrom(const VectorX& start) {
  gaitopt::VariableSet v;
  v.names = {"a", "b", "c"};
  v.lower = VectorX::Constant(3, -5.0);
  v.upper = VectorX::Constant(3, 5.0);
  v.initial = start;
  return v;
}

gaitopt::NlpProblem makeProblem(const VectorX& start) {
  gaitopt::NlpProblem p(boxFrom(start));
  p.addCost(std::make_unique<ShiftedQuadratic>());
  p.addConstraints(std::make_unique<DiscAndPlane>());
  return p;
}

}  // namespace

TEST_CASE("ipopt: a warm start reaches the cold optimum, faster than a primal-only restart", "[ipopt]") {
  const gaitopt::HessianMode mode =
      GENERATE(gaitopt::HessianMode::DenseBfgs, gaitopt::HessianMode::Exact,
               gaitopt::HessianMode::LimitedMemory);
  gaitopt::NlpSettings settings;
  settings.hessian = mode;
  settings.tol = 1e-10;
  settings.print_every = 0;
  gaitopt::NlpProblem cold_problem = makeProblem(VectorX::Zero(3));
  const gaitopt::NlpSolution cold = gaitopt::solveWithIpopt(cold_problem, settings);
  INFO("Hessian mode " << static_cast<int>(mode) << ", cold: " << cold.iterations
                       << " iterations, objective " << cold.objective);
  REQUIRE(cold.status == gaitopt::NlpStatus::Solved);
  // The disc is active and its multiplier positive (KKT: ∇f = −λ ∇g on the disc).
  CHECK(cold.x.head(2).squaredNorm() == Approx(1.0).epsilon(1e-7));
  REQUIRE(cold.multipliers.lambda.size() == 2);
  CHECK(cold.multipliers.lambda(0) > 0.1);
  CHECK(std::abs(cold.multipliers.lambda(1)) < 1e-6);

  // From the cold optimum moved by 1e-3: without, then with its multipliers.
  const VectorX restart = cold.x + VectorX::Constant(3, 1e-3);
  gaitopt::NlpProblem primal_problem = makeProblem(restart);
  const gaitopt::NlpSolution primal = gaitopt::solveWithIpopt(primal_problem, settings);
  settings.warm_start = cold.multipliers;
  gaitopt::NlpProblem warm_problem = makeProblem(restart);
  const gaitopt::NlpSolution warm = gaitopt::solveWithIpopt(warm_problem, settings);
  INFO("primal-only restart: " << primal.iterations << " iterations; warm: " << warm.iterations
                               << " iterations, objective " << warm.objective);
  REQUIRE(warm.status == gaitopt::NlpStatus::Solved);
  CHECK(std::abs(warm.objective - cold.objective) <= 1e-6 * std::abs(cold.objective));
  CHECK((warm.x - cold.x).norm() <= 1e-6 * cold.x.norm());
  // The multipliers save iterations over restarting from the same point without them.
  CHECK(warm.iterations < primal.iterations);
}

TEST_CASE("ipopt: solves from concurrent threads run one at a time, each at the lone optimum",
          "[ipopt]") {
  gaitopt::NlpSettings settings;
  settings.print_every = 0;
  gaitopt::NlpProblem lone_problem = makeProblem(VectorX::Zero(3));
  const gaitopt::NlpSolution lone = gaitopt::solveWithIpopt(lone_problem, settings);
  REQUIRE(lone.status == gaitopt::NlpStatus::Solved);

  std::atomic<int> inside{0}, most{0};
  constexpr int kThreads = 4;
  std::vector<gaitopt::NlpSolution> solutions(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      gaitopt::NlpProblem p(boxFrom(VectorX::Zero(3)));
      p.addCost(std::make_unique<ConcurrencyProbe>(inside, most));
      p.addConstraints(std::make_unique<DiscAndPlane>());
      solutions[t] = gaitopt::solveWithIpopt(p, settings);
    });
  for (std::thread& t : threads) t.join();
  CHECK(most.load() == 1);
  for (const gaitopt::NlpSolution& s : solutions) {
    CHECK(s.status == gaitopt::NlpStatus::Solved);
    CHECK(s.iterations == lone.iterations);
    CHECK((s.x - lone.x).norm() == 0.0);
  }
}
