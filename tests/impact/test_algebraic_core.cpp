// The templated per-behaviour algebraic impact: impulse–momentum balance, and exact AD
// derivatives against central finite differences.
#include <catch2/catch.hpp>
#include <Eigen/Core>
#include <unsupported/Eigen/AutoDiff>

#include "gaitopt/impact/algebraic_impact_equations.hpp"
#include "impact/impact_test_support.hpp"
#include "test_support.hpp"

using namespace gaitopt;

namespace {

using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, 14, 1>>;

// All outputs of one behaviour stacked: Ẋ⁺ (7), I1, I2, energy loss, slacks.
Eigen::VectorXd stacked(const ImpactOutcome<double>& o) {
  Eigen::VectorXd v(12 + o.slacks.size());
  v << o.Xd_plus, o.impulse1, o.impulse2, o.energy_loss, o.slacks;
  return v;
}

}  // namespace

TEST_CASE("algebraic core: impulse-momentum balance and behaviour equalities", "[impact]") {
  const Model m = test::defaultModel();
  const Vec5 q = test::walkingImpactQ(m);
  const test::FloatingState s =
      test::floatingState(m, q, pinnedVelocityForFoot2(m, q, Vec2(0.3, -0.2)));
  const FloatingTerms<double> t = floatingTerms(m, s.X, s.Xd);
  for (ImpactBehaviour b : allImpactBehaviours()) {
    const ImpactOutcome<double> o = algebraicImpact(m, s.X, s.Xd, b, 0.7);
    // (2.1): A (Ẋ⁺ − Ẋ⁻) = D1ᵀ I1 + D2ᵀ I2
    const Vector7<double> lhs = t.A * (o.Xd_plus - s.Xd);
    const Vector7<double> rhs = t.D1.transpose() * o.impulse1 + t.D2.transpose() * o.impulse2;
    CHECK((lhs - rhs).norm() <= 1e-12 * (1.0 + rhs.norm()));
    const Vec2 V1 = t.D1 * o.Xd_plus, V2 = t.D2 * o.Xd_plus;
    CHECK(std::abs(V2(1)) < 1e-12);  // no bounce (2.2), every behaviour
    if (b.foot1 == Foot1Behaviour::Lift) CHECK(o.impulse1.norm() == 0.0);
    if (b.foot1 == Foot1Behaviour::Stick) CHECK(V1.norm() < 1e-12);
    if (b.foot1 == Foot1Behaviour::SlipPlus) CHECK(o.impulse1(0) == Approx(-0.7 * o.impulse1(1)));
    if (b.foot1 == Foot1Behaviour::SlipMinus) CHECK(o.impulse1(0) == Approx(0.7 * o.impulse1(1)));
    if (b.foot1 != Foot1Behaviour::Lift) CHECK(std::abs(V1(1)) < 1e-12);
    if (b.foot2 == Foot2Behaviour::Stick) CHECK(std::abs(V2(0)) < 1e-12);
    if (b.foot2 == Foot2Behaviour::SlipPlus) CHECK(o.impulse2(0) == Approx(-0.7 * o.impulse2(1)));
    if (b.foot2 == Foot2Behaviour::SlipMinus) CHECK(o.impulse2(0) == Approx(0.7 * o.impulse2(1)));
    CHECK(o.slacks.size() == static_cast<Eigen::Index>(impactSlacks(b).size()));
    const double e_minus = 0.5 * s.Xd.dot(t.A * s.Xd), e_plus = 0.5 * o.Xd_plus.dot(t.A * o.Xd_plus);
    CHECK(o.energy_loss == Approx(e_minus - e_plus).margin(1e-12));
  }
}

TEST_CASE("algebraic core: AD derivatives match finite differences", "[impact]") {
  const Model m = test::defaultModel();
  const Vec5 q = test::walkingImpactQ(m);
  const test::FloatingState s =
      test::floatingState(m, q, pinnedVelocityForFoot2(m, q, Vec2(0.2, -0.3)));
  for (ImpactBehaviour b : allImpactBehaviours()) {
    Vector7<AD> X, Xd;
    for (int i = 0; i < 7; ++i) {
      X(i) = AD(s.X(i), 14, i);
      Xd(i) = AD(s.Xd(i), 14, 7 + i);
    }
    const ImpactOutcome<AD> o = algebraicImpact(m, X, Xd, b, 0.6);
    Eigen::VectorXd value(12 + o.slacks.size());
    Eigen::MatrixXd jac(value.size(), 14);
    const auto put = [&](int row, const AD& x) {
      value(row) = x.value();
      jac.row(row) = x.derivatives().transpose();
    };
    for (int i = 0; i < 7; ++i) put(i, o.Xd_plus(i));
    for (int i = 0; i < 2; ++i) put(7 + i, o.impulse1(i));
    for (int i = 0; i < 2; ++i) put(9 + i, o.impulse2(i));
    put(11, o.energy_loss);
    for (Eigen::Index i = 0; i < o.slacks.size(); ++i) put(12 + static_cast<int>(i), o.slacks(i));
    CHECK((value - stacked(algebraicImpact(m, s.X, s.Xd, b, 0.6))).norm() < 1e-12);
    const double h = 1e-6;
    for (int k = 0; k < 14; ++k) {
      Vector7<double> Xp = s.X, Xm = s.X, Xdp = s.Xd, Xdm = s.Xd;
      (k < 7 ? Xp(k) : Xdp(k - 7)) += h;
      (k < 7 ? Xm(k) : Xdm(k - 7)) -= h;
      const Eigen::VectorXd fd = (stacked(algebraicImpact(m, Xp, Xdp, b, 0.6)) -
                                  stacked(algebraicImpact(m, Xm, Xdm, b, 0.6))) / (2.0 * h);
      INFO("behaviour " << toString(b.foot1) << "/" << toString(b.foot2) << ", variable " << k);
      CHECK((jac.col(k) - fd).norm() <= 1e-6 * (1.0 + fd.norm()));
    }
  }
}
