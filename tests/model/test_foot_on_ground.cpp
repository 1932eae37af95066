// projectFoot2OnGround: a configuration a few micrometres off double support is moved onto it
// by the least change of q.
#include <catch2/catch.hpp>

#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/foot_on_ground.hpp"
#include "impact/impact_test_support.hpp"
#include "test_support.hpp"

using namespace gaitopt;

namespace {
double foot2Height(const Model& m, const Vec5& q) {
  return pinnedTerms(m, q, Vec5(Vec5::Zero())).foot2(1);
}
}  // namespace

TEST_CASE("projectFoot2OnGround: micrometres off the ground to 1e-12 m, least-norm change",
          "[model][ground_projection]") {
  const Model m = test::defaultModel();
  const Vec5 on_ground = test::walkingImpactQ(m);
  REQUIRE(std::abs(foot2Height(m, on_ground)) < 1e-12);
  for (const double offset : {3e-7, -2e-6, 8e-6}) {
    Vec5 q = on_ground;
    q(3) += offset;  // the inter-leg angle: foot 2 leaves the ground by ~ leg length × offset
    const double z2 = foot2Height(m, q);
    const GroundProjection p = projectFoot2OnGround(m, q);
    INFO("offset " << offset << ", z2 " << z2);
    CHECK(p.converged);
    CHECK(p.height == Approx(z2).epsilon(1e-12));
    CHECK(std::abs(foot2Height(m, p.q)) <= kGroundProjectionTolerance);
    // Least norm: Δq is along ∂z2/∂q at q, and its size is |z2| / |∂z2/∂q| to first order.
    const Vec5 J = pinnedTerms(m, q, Vec5(Vec5::Zero())).D2.row(1).transpose();
    const Vec5 dq = p.q - q;
    CHECK(std::abs(dq.dot(J)) / (dq.norm() * J.norm()) == Approx(1.0).margin(1e-6));
    CHECK(dq.norm() == Approx(std::abs(z2) / J.norm()).epsilon(1e-4));
    CHECK(p.max_change == Approx(dq.cwiseAbs().maxCoeff()));
  }
}

TEST_CASE("projectFoot2OnGround: a configuration on the ground is unchanged",
          "[model][ground_projection]") {
  const Model m = test::defaultModel();
  const Vec5 q = test::walkingImpactQ(m);
  const GroundProjection p = projectFoot2OnGround(m, q);
  CHECK(p.converged);
  CHECK(p.q == q);
  CHECK(p.max_change == 0.0);
}
