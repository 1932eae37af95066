// The drawing and plotting columns of the sampled trajectory: joint points at the link lengths
// and consistent with foot 2, speeds and envelope as the constraints see them, the zero-dynamics
// energy conserved over the single support, and the clearance parabola (3.49).
#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/model/joint_friction.hpp"
#include "test_gait_support.hpp"

using namespace gaitopt;

TEST_CASE("trajectory drawing points sit at the link lengths", "[trajectory]") {
  const GaitEvaluator ev = test::defaultGaitEvaluator();
  const RobotParams& p = ev.model().robot;
  const GaitEvaluation<double> e = ev.evaluate(test::optimalStep());
  REQUIRE(e.motion_computed);
  for (const TrajectoryRow& r : sampleTrajectory(ev, e, 500.0)) {
    CHECK(r.knee1.norm() == Approx(p.l1).epsilon(1e-12));  // foot 1 at the origin
    CHECK((r.hip - r.knee1).norm() == Approx(p.l2).epsilon(1e-12));
    CHECK((r.knee2 - r.hip).norm() == Approx(p.l4).epsilon(1e-12));
    CHECK((r.foot2 - r.knee2).norm() == Approx(p.l5).epsilon(1e-12));
    CHECK((r.head - r.hip).norm() == Approx(p.trunk_length).epsilon(1e-12));
    CHECK(r.head(1) > r.hip(1));  // upright-ish trunk
  }
}

TEST_CASE("trajectory speeds, envelope, energy and clearance columns", "[trajectory]") {
  const GaitEvaluator ev = test::defaultGaitEvaluator();
  const GaitEvaluation<double> e = ev.evaluate(test::optimalStep());
  REQUIRE(e.defined());
  const std::vector<TrajectoryRow> rows = sampleTrajectory(ev, e, 500.0);
  double e_min = 1e300, e_max = -1e300, e_scale = 0.0;
  for (const TrajectoryRow& r : rows) {
    CHECK((r.omega - jointSpeeds(r.qd)).norm() < 1e-12);
    for (int j = 0; j < 4; ++j) {
      CHECK(r.gamma_max(j) <= 140.0 + 1e-12);  // the default envelope's plateau
      CHECK(std::abs(r.gamma_star(j)) <= r.gamma_max(j) + 1e-6);  // every constraint holds
    }
    const double x = r.foot2(0) / e.step_length;
    CHECK(r.clearance == Approx(0.03 * (1.0 - x * x)).margin(1e-15));
    CHECK(r.zd_potential.has_value() == (r.phase == Phase::SingleSupport));
    if (!r.zd_potential) continue;
    const double energy = 0.5 * r.sigma * r.sigma + *r.zd_potential;  // (3.14)
    e_min = std::min(e_min, energy);
    e_max = std::max(e_max, energy);
    e_scale = std::max(e_scale, 0.5 * r.sigma * r.sigma);
  }
  CHECK(e_max - e_min < 1e-8 * e_scale);
  // A ground foot in DS: clearance bound 0 at the rear foot x = −d.
  CHECK(rows.back().clearance == Approx(0.0).margin(1e-12));
}
