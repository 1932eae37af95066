// The drawing and plotting columns of the sampled trajectory: joint points at the link lengths
// and consistent with foot 2, joint speeds as the rotation rates of the drawn links, the envelope
// as the constraints see it, the zero-dynamics energy conserved over the single support, and the
// clearance bound (3.49): zero where the swing foot touches the ground, the configured height at
// mid-stride, below the swing foot.
#include <algorithm>
#include <array>
#include <cmath>

#include <catch2/catch.hpp>

#include "gaitopt/gait/trajectory.hpp"
#include "test_gait_support.hpp"

using namespace gaitopt;

namespace {

// Rotation of link vector a(t0) → a(t1) [rad], without wrapping.
double rotation(const Vec2& a0, const Vec2& a1) {
  return std::atan2(a0(0) * a1(1) - a0(1) * a1(0), a0.dot(a1));
}

// Joint speeds by central differences of the drawn links' directions between rows r0 and r1:
// each joint's relative rotation rate with the motor sign of (1.19), knee 1 = femur 1 against
// tibia 1, hip 1 = trunk against femur 1, hip 2 = trunk against femur 2, knee 2 = femur 2
// against tibia 2.
Vec4 linkJointSpeeds(const TrajectoryRow& r0, const TrajectoryRow& r1) {
  const auto links = [](const TrajectoryRow& r) {
    return std::array<Vec2, 5>{r.knee1, r.hip - r.knee1, r.head - r.hip, r.knee2 - r.hip,
                               r.foot2 - r.knee2};
  };
  const std::array<Vec2, 5> a = links(r0), b = links(r1);
  std::array<double, 5> rate;
  for (int k = 0; k < 5; ++k) rate[k] = rotation(a[k], b[k]) / (r1.t - r0.t);
  return Vec4(rate[1] - rate[0], rate[2] - rate[1], rate[2] - rate[3], rate[3] - rate[4]);
}

}  // namespace

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
  // ω against central differences on a 5 kHz sampling, where its error O(h²) is small; rows
  // around a phase end (the exact end row is closer) left out.
  const std::vector<TrajectoryRow> fine = sampleTrajectory(ev, e, 5000.0);
  for (std::size_t i = 1; i + 1 < fine.size(); ++i) {
    const double h0 = fine[i].t - fine[i - 1].t, h1 = fine[i + 1].t - fine[i].t;
    if (fine[i - 1].phase != fine[i + 1].phase || std::abs(h1 - h0) > 1e-12) continue;
    const Vec4 omega = linkJointSpeeds(fine[i - 1], fine[i + 1]);
    for (int j = 0; j < 4; ++j)
      CHECK(fine[i].omega(j) == Approx(omega(j)).margin(1e-4 * (1.0 + std::abs(omega(j)))));
  }
  for (const TrajectoryRow& r : rows) {
    for (int j = 0; j < 4; ++j) {
      CHECK(r.gamma_max(j) <= 140.0 + 1e-12);  // the default envelope's plateau
      CHECK(std::abs(r.gamma_star(j)) <= r.gamma_max(j) + 1e-6);  // every constraint holds
    }
    CHECK(r.clearance >= -1e-15);
    CHECK(r.clearance <= 0.03 + 1e-15);
    // The step meets the bound at the nodes; between them it dips by tens of micrometres.
    if (r.phase == Phase::SingleSupport) CHECK(r.foot2(1) >= r.clearance - 1e-4);
    CHECK(r.zd_potential.has_value() == (r.phase == Phase::SingleSupport));
    if (!r.zd_potential) continue;
    const double energy = 0.5 * r.sigma * r.sigma + *r.zd_potential;  // (3.14)
    e_min = std::min(e_min, energy);
    e_max = std::max(e_max, energy);
    e_scale = std::max(e_scale, 0.5 * r.sigma * r.sigma);
  }
  CHECK(e_max - e_min < 1e-8 * e_scale);
  // The swing foot on the ground at both ends of the single support (lift-off behind, landing
  // in front), and the rear foot in DS: bound 0 there.
  const auto ss_end = std::find_if(rows.begin(), rows.end(), [](const TrajectoryRow& r) {
                        return r.phase != Phase::SingleSupport;
                      }) - 1;
  for (const TrajectoryRow* r : {&rows.front(), &*ss_end, &rows.back()}) {
    CHECK(std::abs(r->foot2(1)) < 1e-9);
    CHECK(r->clearance == Approx(0.0).margin(1e-12));
  }
  // The configured 0.03 m where the swing foot passes the stance foot (x = 0).
  for (auto r = rows.begin(); r + 1 <= ss_end; ++r) {
    if (r->foot2(0) > 0.0 || (r + 1)->foot2(0) <= 0.0) continue;
    const double w = -r->foot2(0) / ((r + 1)->foot2(0) - r->foot2(0));
    CHECK((1.0 - w) * r->clearance + w * (r + 1)->clearance == Approx(0.03).margin(1e-5));
  }
}
