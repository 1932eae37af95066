// The single support's apex energy from the gait's zero dynamics (control/apex_energy.hpp),
// checked against the gait's own sampled motion (gait/trajectory.hpp), not against its tables.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "gaitopt/control/apex_energy.hpp"
#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "test_default_gait.hpp"

namespace gaitopt::test {
namespace {

TrajectoryRow ssRow(const ShippedGait& g, double fraction) {
  return sampleTrajectoryAt(g.evaluator, g.evaluation, Phase::SingleSupport,
                            fraction * g.evaluation.motion.T_SS);
}

}  // namespace

TEST_CASE("Stance momentum is the gait's angular momentum about the foot and M g x_G",
          "[control][apex_energy]") {
  const DefaultGait g;
  for (double f : {0.0, 0.3, 0.8}) {
    const TrajectoryRow r = ssRow(g, f);
    const StanceMomentum m = stanceMomentum(g.model, r.q, r.qd);
    CHECK(m.sigma == Approx(r.sigma).epsilon(1e-12));
    CHECK(m.gravity_torque ==
          Approx(g.model.total_mass * g.model.gravity * r.com(0)).epsilon(1e-12));
    CHECK(m.gravity_torque == Approx(pinnedTerms(g.model, r.q, r.qd).G(0)).epsilon(1e-9));
  }
}

TEST_CASE("Apex energy: the gait's own motion predicts its own apex all along the step",
          "[control][apex_energy]") {
  for (const char* path : {"configs/gait/default_step.yaml", "configs/gait/optimal_0.3.yaml"}) {
    const ShippedGait g(path);
    const ApexEnergy apex(g.model, g.evaluation.motion);
    // The gait's apex: the smallest σ² of its sampled single support.
    double smallest = 1e300;
    for (int k = 0; k <= 400; ++k) smallest = std::min(smallest, std::pow(ssRow(g, k / 400.0).sigma, 2));
    CHECK(apex.gait() > 0.0);
    CHECK(apex.gait() == Approx(smallest).epsilon(2e-3));
    // σ² − Φ is conserved on the path: every state of the step predicts the same apex.
    for (double f : {0.0, 0.2, 0.4}) {
      const TrajectoryRow r = ssRow(g, f);
      const StanceMomentum m = stanceMomentum(g.model, r.q, r.qd);
      CHECK(apex.predicted(r.q(0), m.sigma, m.gravity_torque) == Approx(apex.gait()).epsilon(5e-3));
    }
    // Past the apex only the kinetic part is left.
    const TrajectoryRow end = ssRow(g, 1.0);
    CHECK(apex.predicted(end.q(0), end.sigma, 0.0) == Approx(end.sigma * end.sigma).epsilon(1e-9));
  }
}

TEST_CASE("Apex energy falls below the gait's for a slower state, a lean back or a reversed rate",
          "[control][apex_energy]") {
  const ShippedGait g("configs/gait/optimal_0.3.yaml");
  const ApexEnergy apex(g.model, g.evaluation.motion);
  const TrajectoryRow r = ssRow(g, 0.1);
  const StanceMomentum m = stanceMomentum(g.model, r.q, r.qd);
  const double on_path = apex.predicted(r.q(0), m.sigma, m.gravity_torque);
  // 10 % slower: σ² × 0.81; the gait's apex margin is small, so the apex energy drops by far
  // more than 19 %.
  const double slower = apex.predicted(r.q(0), 0.9 * m.sigma, m.gravity_torque);
  CHECK(on_path - slower == Approx(0.19 * m.sigma * m.sigma).epsilon(1e-9));
  CHECK(slower < 0.5 * apex.gait());
  // The centre of mass 1 cm behind its path until the apex: gravity takes more momentum.
  const double behind = apex.predicted(r.q(0), m.sigma,
                                       m.gravity_torque - 0.01 * g.model.total_mass * g.model.gravity);
  CHECK(behind < on_path);
  // Turning back: negative.
  CHECK(apex.predicted(r.q(0), -m.sigma, m.gravity_torque) < 0.0);
  // The start-rate scale that keeps a fraction of the gait's apex energy: the energy at that
  // scale is that fraction.
  const double a0 = g.evaluation.motion.q_iSS(0);
  CHECK(apex.fromStart(a0, 1.0, 0.0) == Approx(apex.gait()).epsilon(1e-9));
  const double k = apex.minStartRateScale(a0, 0.5);
  CHECK(k < 1.0);
  CHECK(k > 0.9);  // a 0.3 m/s gait with an apex margin of about a fifth of its start energy
  CHECK(apex.fromStart(a0, k, 0.0) == Approx(0.5 * apex.gait()).epsilon(1e-9));
}

}  // namespace gaitopt::test
