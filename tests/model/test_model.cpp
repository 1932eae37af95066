// The dynamic model: structure (symmetry, skew-symmetry, energy), the thesis' conventions and
// regression values (digest §1–2), pinned ≡ floating constrained, and exact derivatives.
#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "gaitopt/model/dynamics_floating.hpp"
#include "gaitopt/model/forward_dynamics.hpp"
#include "gaitopt/model/derivatives.hpp"
#include "test_support.hpp"

using namespace gaitopt;
using gaitopt::test::RandomStates;

namespace {
const Vec5 q0(0.0, -M_PI, -M_PI, 0.0, -M_PI);
const Vec5 qt(0.2, -M_PI + 0.2, -M_PI - 0.1, 0.3, -M_PI + 0.4);

Model frictionless(Model m) {
  m.coulomb.setZero();
  m.viscous.setZero();
  return m;
}
}  // namespace

TEST_CASE("support bar folds into the trunk as in (1.24)", "[model]") {
  const Model m = test::defaultModel();
  CHECK(m.mass(2) == Approx(23.5).epsilon(1e-14));
  CHECK(m.com_offset(2) == Approx(0.136340).margin(5e-7));
  CHECK(m.inertia(2) == Approx(2.424766).margin(5e-7));
  CHECK(m.total_mass == Approx(43.5).epsilon(1e-14));
  const Model nobar = buildModel(test::robotFile("rabbit_miossec_nobar"));
  CHECK(nobar.total_mass == Approx(36.0).epsilon(1e-14));
  CHECK(nobar.com_offset(2) == Approx(0.20025).epsilon(1e-14));
}

TEST_CASE("upright configuration: hip at 0.8 m, foot 2 at the origin", "[model]") {
  const Model m = test::defaultModel();
  const PinnedTerms<double> t = pinnedTerms(m, q0, Vec5(Vec5::Zero()));
  const Vec2 hip = pinnedHip(m, q0);
  CHECK(hip(0) == Approx(0.0).margin(1e-15));
  CHECK(hip(1) == Approx(0.8).epsilon(1e-15));
  CHECK(t.foot2.norm() < 1e-15);
  // Trunk CoM with the bar at 0.8 + s3* (digest §2.10).
  Vector7<double> X, Xd;
  floatingStateFromPinned(m, q0, Vec5(Vec5::Zero()), X, Xd);
  CHECK(X(6) == Approx(0.93634).margin(5e-6));
}

TEST_CASE("regression values of digest §2.10", "[model]") {
  const Model m = test::defaultModel();
  Mat5 expected;
  expected << 29.7248, 16.7534, -5.39227, -0.799506, -0.0056528,  //
      16.7534, 11.3984, -4.11067, 0.318414, -0.168213,            //
      -5.39227, -4.11067, 4.45586, 0.8134, 0,                     //
      -0.799506, 0.318414, 0.8134, 2.24973, -0.330773,            //
      -0.0056528, -0.168213, 0, -0.330773, 0.981613;
  const PinnedTerms<double> t0 = pinnedTerms(m, q0, Vec5(Vec5::Zero()));
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      INFO("A(" << i << "," << j << ")");
      CHECK(t0.A(i, j) == Approx(expected(i, j)).margin(6e-5));
    }
  const PinnedTerms<double> tt = pinnedTerms(m, qt, Vec5(Vec5::Zero()));
  const Vec5 G_expected(-89.263, -56.144, 15.069, 16.272, -1.1782);
  const Vec5 A1_expected(29.6549, 16.7427, -5.32862, -0.663924, 0.00555528);
  for (int i = 0; i < 5; ++i) {
    CHECK(tt.G(i) == Approx(G_expected(i)).margin(6e-4));
    CHECK(tt.A(0, i) == Approx(A1_expected(i)).margin(6e-5));
  }
  // α-row of gravity is the moment of the weight about foot 1 (digest §2.8).
  CHECK(tt.G(0) == Approx(m.total_mass * m.gravity * tt.com(0)).epsilon(1e-13));
}

TEST_CASE("inertia matrix is symmetric positive definite", "[model]") {
  const Model m = test::defaultModel();
  RandomStates rs;
  for (int n = 0; n < 200; ++n) {
    const PinnedTerms<double> t = pinnedTerms(m, rs.q(), rs.qd());
    CHECK((t.A - t.A.transpose()).norm() < 1e-13);
    Eigen::SelfAdjointEigenSolver<Mat5> eig(t.A);
    CHECK(eig.eigenvalues().minCoeff() > 1e-3);
  }
}

TEST_CASE("Ȧ − 2C is skew-symmetric with C from Christoffel symbols", "[model]") {
  const Model m = test::defaultModel();
  RandomStates rs;
  for (int n = 0; n < 50; ++n) {
    const Vec5 q = rs.q(), qd = rs.qd();
    const PinnedDerivatives d = pinnedTermsDerivatives(m, q, qd);
    Mat5 Adot = Mat5::Zero(), Cmat = Mat5::Zero();
    for (int k = 0; k < 5; ++k) Adot += d.dA_dq[k] * qd(k);
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j)
        for (int k = 0; k < 5; ++k)
          Cmat(i, j) += 0.5 * (d.dA_dq[k](i, j) + d.dA_dq[j](i, k) - d.dA_dq[i](j, k)) * qd(k);
    const Mat5 N = Adot - 2.0 * Cmat;
    CHECK((N + N.transpose()).norm() < 1e-12 * (1.0 + N.norm()));
    CHECK((Cmat * qd - d.value.C).norm() < 1e-12 * (1.0 + d.value.C.norm()));
  }
}

TEST_CASE("passive pinned motion conserves energy over 2 s", "[model]") {
  const Model m = frictionless(test::defaultModel());
  PinnedState x0{Vec5(0.05, -M_PI + 0.3, -M_PI + 0.1, -0.2, -M_PI + 0.2),
                 Vec5(-0.5, 0.3, -0.2, 0.4, 0.1)};
  const TorqueLaw zero = [](double, const PinnedState&) { return Vec4(Vec4::Zero()); };
  const double e0 = pinnedEnergy(m, x0.q, x0.qd);
  const PinnedState x1 = simulateSS(m, x0, zero, 2.0, 1e-4, SignMode::Exact);
  const double e1 = pinnedEnergy(m, x1.q, x1.qd);
  INFO("E0 = " << e0 << ", E1 = " << e1);
  CHECK(std::abs(e1 - e0) <= 1e-8 * std::abs(e0));
  // The robot actually moved (the check is not vacuous).
  CHECK((x1.q - x0.q).norm() > 0.1);
}

TEST_CASE("pinned model equals the floating model constrained at foot 1", "[model]") {
  const Model m = test::defaultModel();
  RandomStates rs;
  for (int n = 0; n < 20; ++n) {
    const Vec5 q = rs.q(), qd = rs.qd();
    const Vec4 gamma_star(10.0, -20.0, 5.0, 30.0);
    const Vec5 qdd = forwardDynamicsSS(m, q, qd, gamma_star, SignMode::Exact);

    Vector7<double> X, Xd;
    floatingStateFromPinned(m, q, qd, X, Xd);
    const FloatingTerms<double> f = floatingTerms(m, X, Xd);
    CHECK((f.X.tail<2>() - pinnedTerms(m, q, qd).com).norm() > 0.0);  // trunk CoM, not whole CoM
    CHECK((f.D1 * Xd).norm() < 1e-13);                               // foot 1 at rest
    // KKT system of (1.1) with (1.6): [A −D1ᵀ; D1 0] [Ẍ; R1] = [D_Γ Γ − C − G; −H1].
    const Vec4 gamma = gamma_star - frictionTorque(m, jointSpeeds(qd), SignMode::Exact);
    Eigen::Matrix<double, 9, 9> K = Eigen::Matrix<double, 9, 9>::Zero();
    K.topLeftCorner<7, 7>() = f.A;
    K.block<7, 2>(0, 7) = -f.D1.transpose();
    K.block<2, 7>(7, 0) = f.D1;
    Eigen::Matrix<double, 9, 1> rhs;
    rhs.head<5>() = m.D_Gamma * gamma;
    rhs.segment<2>(5).setZero();
    rhs.head<7>() -= f.C + f.G;
    rhs.tail<2>() = -f.H1;
    const Eigen::Matrix<double, 9, 1> sol = K.partialPivLu().solve(rhs);
    CHECK((sol.head<5>() - qdd).norm() < 1e-10 * (1.0 + qdd.norm()));
    const auto id = inverseDynamicsSS(m, q, qd, qdd, SignMode::Exact);
    CHECK((sol.tail<2>() - id.R1).norm() < 1e-9 * (1.0 + id.R1.norm()));
    CHECK(std::abs(id.alpha_row_residual) < 1e-10);
    CHECK((id.gamma_star - gamma_star).norm() < 1e-10);
  }
}

TEST_CASE("model derivatives equal central finite differences", "[model][derivatives]") {
  const Model m = test::defaultModel();
  RandomStates rs;
  const double h = 1e-6;
  const auto rel = [](double a, double b) { return std::abs(a - b) / std::max(1.0, std::abs(b)); };
  for (int n = 0; n < 10; ++n) {
    const Vec5 q = rs.q(), qd = rs.qd();
    const PinnedDerivatives d = pinnedTermsDerivatives(m, q, qd);
    for (int k = 0; k < 10; ++k) {
      Vec5 qp = q, qm = q, qdp = qd, qdm = qd;
      if (k < 5) {
        qp(k) += h;
        qm(k) -= h;
      } else {
        qdp(k - 5) += h;
        qdm(k - 5) -= h;
      }
      const PinnedTerms<double> tp = pinnedTerms(m, qp, qdp), tm = pinnedTerms(m, qm, qdm);
      const Vec5 dC = (tp.C - tm.C) / (2 * h), dG = (tp.G - tm.G) / (2 * h);
      const Vec2 dH2 = (tp.H2 - tm.H2) / (2 * h);
      for (int i = 0; i < 5; ++i) {
        CHECK(rel(k < 5 ? d.dC_dq(i, k) : d.dC_dqd(i, k - 5), dC(i)) < 1e-6);
        if (k < 5) CHECK(rel(d.dG_dq(i, k), dG(i)) < 1e-6);
      }
      for (int i = 0; i < 2; ++i) CHECK(rel(k < 5 ? d.dH2_dq(i, k) : d.dH2_dqd(i, k - 5), dH2(i)) < 1e-6);
      if (k < 5) {
        const Mat5 dA = (tp.A - tm.A) / (2 * h);
        const Matrix25<double> dD2 = (tp.D2 - tm.D2) / (2 * h);
        CHECK((d.dA_dq[k] - dA).cwiseAbs().maxCoeff() < 1e-6);
        CHECK((d.dD2_dq[k] - dD2).cwiseAbs().maxCoeff() < 1e-6);
      } else {
        CHECK((tp.A - tm.A).norm() == 0.0);  // A does not depend on q̇
      }
    }
  }
}

TEST_CASE("inverse-dynamics derivatives equal central finite differences", "[model][derivatives]") {
  const Model m = test::defaultModel();
  RandomStates rs;
  const double h = 1e-6;
  for (int n = 0; n < 5; ++n) {
    Eigen::Matrix<double, 15, 1> x;
    x << rs.q(), rs.qd(), rs.qd() * 3.0;
    const auto eval = [&](const Eigen::Matrix<double, 15, 1>& v) {
      return inverseDynamicsSS(m, Vec5(v.head<5>()), Vec5(v.segment<5>(5)), Vec5(v.tail<5>()),
                               SignMode::Smooth);
    };
    const auto d = inverseDynamicsSSDerivatives(m, Vec5(x.head<5>()), Vec5(x.segment<5>(5)),
                                                Vec5(x.tail<5>()), SignMode::Smooth);
    for (int k = 0; k < 15; ++k) {
      Eigen::Matrix<double, 15, 1> xp = x, xm = x;
      xp(k) += h;
      xm(k) -= h;
      const auto rp = eval(xp), rm = eval(xm);
      const Vec4 dg = (rp.gamma_star - rm.gamma_star) / (2 * h);
      const Vec2 dR = (rp.R1 - rm.R1) / (2 * h);
      for (int i = 0; i < 4; ++i)
        CHECK(std::abs(d.dgamma_star(i, k) - dg(i)) < 1e-6 * std::max(1.0, std::abs(dg(i))));
      for (int i = 0; i < 2; ++i)
        CHECK(std::abs(d.dR1(i, k) - dR(i)) < 1e-6 * std::max(1.0, std::abs(dR(i))));
      const double dres = (rp.alpha_row_residual - rm.alpha_row_residual) / (2 * h);
      CHECK(std::abs(d.dalpha_row_residual(k) - dres) < 1e-6 * std::max(1.0, std::abs(dres)));
    }
  }
}

TEST_CASE("friction follows the virtual work (1.20) and the sign of (1.21)", "[model][friction]") {
  const Model m = test::defaultModel();
  const Vec5 qd(0.3, 0.7, -0.4, 0.9, -1.2);  // δ̇2 + δ̇3 = 0.5 > 0
  const Vec4 w = jointSpeeds(qd);
  CHECK(w(0) == 0.7);
  CHECK(w(1) == 0.4);
  CHECK(w(2) == Approx(-0.5).epsilon(1e-15));
  CHECK(w(3) == -1.2);
  const Vec4 f = frictionTorque(m, w, SignMode::Exact);
  // Generalised friction force −D_Γ f must equal the coefficients of (1.20).
  const Vec5 Q = -m.D_Gamma * f;
  const auto fr = [&](int j, double v) { return m.coulomb(j) * (v > 0 ? 1 : -1) + m.viscous(j) * v; };
  CHECK(Q(0) == 0.0);
  CHECK(Q(1) == Approx(-fr(0, qd(1))).epsilon(1e-14));
  CHECK(Q(2) == Approx(-fr(1, qd(2)) - fr(2, qd(2) + qd(3))).epsilon(1e-14));
  CHECK(Q(3) == Approx(-fr(2, qd(2) + qd(3))).epsilon(1e-14));
  CHECK(Q(4) == Approx(-fr(3, qd(4))).epsilon(1e-14));
  // Friction dissipates, and Γ* − Γ is that friction torque (1.21).
  CHECK(w.dot(f) > 0.0);
  const auto id = inverseDynamicsSS(m, Vec5(0.1, -2.8, -3.0, 0.2, -2.9), qd, Vec5(Vec5::Zero()),
                                    SignMode::Exact);
  CHECK(((id.gamma_star - id.gamma) - f).norm() < 1e-12);
  // The smooth sign tends to the exact one away from zero speed.
  const Vec4 fs = frictionTorque(m, w, SignMode::Smooth);
  CHECK((fs - f).norm() < 1e-3);
}

TEST_CASE("high-gear rotor approximation differs only by the carrier-speed terms", "[model]") {
  ModelOptions hg;
  hg.rotor = RotorModel::HighGear;
  const Model exact = test::defaultModel(), approx = test::defaultModel(hg);
  const double N = 50.0, Im = 3.32e-4;
  const PinnedTerms<double> a = pinnedTerms(exact, q0, Vec5(Vec5::Zero()));
  const PinnedTerms<double> b = pinnedTerms(approx, q0, Vec5(Vec5::Zero()));
  // α–α entry: exact rotors add 4 Im (each rotor's carrier turns with α), approximation none.
  CHECK(a.A(0, 0) - b.A(0, 0) == Approx(4 * Im).epsilon(1e-9));
  // δ4–δ4: exact (−N)² + 0 vs N²: equal; δ1–δ1: (1−N)² + 1 + 1 + 1 vs N².
  CHECK(a.A(4, 4) - b.A(4, 4) == Approx(0.0).margin(1e-12));
  CHECK(a.A(1, 1) - b.A(1, 1) == Approx(Im * ((1 - N) * (1 - N) + 3 - N * N)).epsilon(1e-9));
}
