// The `inertial` candidate's pieces (ident/inertial_fit.hpp): the barycentric parameters round
// trip, the residuals are affine in them, base parameters by QR regroup a dependent column,
// the constrained least squares stays physically consistent where the unconstrained one is not.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <random>

#include "gaitopt/ident/inertial_fit.hpp"
#include "test_support.hpp"

using namespace gaitopt;

TEST_CASE("inertial parameters round trip and tie the legs", "[ident][inertial]") {
  RobotParams r = test::robotFile("rabbit_miossec");
  r.trunk_com_shift = 0.02;
  const Eigen::VectorXd p = inertialParameters(r);
  CHECK(p(0) == Approx(3.2));
  CHECK(p(1) == Approx(3.2 * 0.127));
  CHECK(p(2) == Approx(0.1 + 3.2 * 0.127 * 0.127));
  CHECK(p(7) == Approx(16.0 * (0.20025 + 0.02)));  // the trunk CoM as the dynamics see it
  Eigen::VectorXd d = Eigen::VectorXd::Zero(kNumInertialParameters);
  d << 0.5, 0.05, 0.02, -0.3, 0.01, 0.03, 2.0, -0.1, 0.2;
  const RobotParams c = withInertialChange(r, d);
  CHECK((inertialParameters(c) - (p + d)).norm() < 1e-12);
  CHECK(c.mass[0] == Approx(c.mass[4]));  // both tibias
  CHECK(c.inertia[1] == Approx(c.inertia[3]));  // both femurs
  CHECK(c.s[2] == Approx((p(7) + d(7)) / (p(6) + d(6)) - 0.02));
  CHECK((inertialParameters(withInertialChange(r, -d * 0.0)) - p).norm() < 1e-12);
}

TEST_CASE("base parameters regroup a dependent column", "[ident][inertial]") {
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd Y(200, kNumInertialParameters);
  for (Eigen::Index i = 0; i < Y.size(); ++i) Y.data()[i] = n(rng);
  Y.col(8) = 2.0 * Y.col(6) - 0.5 * Y.col(1);  // J_trunk's column a combination of two others
  const BaseParameters b = baseParameters(Y);
  REQUIRE(b.rank == 8);
  REQUIRE(b.dependent.size() == 1);
  // Any p and p + null-space direction give the same base values and the same Y p.
  Eigen::VectorXd p = Eigen::VectorXd::Random(kNumInertialParameters);
  Eigen::VectorXd null = Eigen::VectorXd::Zero(kNumInertialParameters);
  null(8) = 1.0;
  null(6) = -2.0;
  null(1) = 0.5;
  CHECK((Y * null).norm() < 1e-9 * Y.norm());
  CHECK((b.values(p) - b.values(p + 0.7 * null)).norm() < 1e-9);
  // Y p depends on p only through the base values: Y_independent β = Y p.
  Eigen::MatrixXd Yb(Y.rows(), b.rank);
  for (int i = 0; i < b.rank; ++i) Yb.col(i) = Y.col(b.independent[i]);
  CHECK((Yb * b.values(p) - Y * p).norm() < 1e-9 * (Y * p).norm());
}

TEST_CASE("consistent least squares keeps every link physical", "[ident][inertial]") {
  const RobotParams r = test::robotFile("rabbit_miossec");
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd Y(300, kNumInertialParameters);
  for (Eigen::Index i = 0; i < Y.size(); ++i) Y.data()[i] = n(rng);
  SECTION("an interior optimum is the least-squares one") {
    Eigen::VectorXd truth = Eigen::VectorXd::Zero(kNumInertialParameters);
    truth(6) = 1.5;   // +1.5 kg trunk
    truth(8) = 0.4;   // +0.4 kg·m² trunk about the hip
    const ConsistentFit f = consistentLeastSquares(Y, -Y * truth, r, 0.0);
    CHECK(f.active.empty());
    CHECK((f.delta - truth).norm() < 1e-8);
  }
  SECTION("an unphysical optimum is projected onto the consistent set") {
    // The data ask for a trunk inertia about its CoM of I3 − 3 < 0.
    Eigen::VectorXd truth = Eigen::VectorXd::Zero(kNumInertialParameters);
    truth(8) = -3.0;
    const ConsistentFit f = consistentLeastSquares(Y, -Y * truth, r, 0.0);
    REQUIRE(f.active == std::vector<std::string>{"I3 > 0"});
    const RobotParams c = withInertialChange(r, f.delta);
    for (int i = 0; i < 5; ++i) {
      CHECK(c.mass[i] > 0.0);
      CHECK(c.inertia[i] > 0.0);
      CHECK(c.s[i] > 0.0);
    }
    CHECK(c.inertia[2] < 1e-3);  // on the boundary: the closest physical trunk
    // Optimal on the constraint: no consistent point nearby has a lower objective.
    const double best = (Y * (f.delta - truth)).squaredNorm();
    for (int k = 0; k < 20; ++k) {
      const Eigen::VectorXd t = f.delta + 1e-3 * Eigen::VectorXd::Random(kNumInertialParameters);
      if (withInertialChange(r, t).inertia[2] > 0.0) CHECK((Y * (t - truth)).squaredNorm() >= best * (1 - 1e-9));
    }
  }
}
