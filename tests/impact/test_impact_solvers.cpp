// Algebraic and differential impact solvers: physical laws on every returned solution, the
// thesis' findings (§2.4.6, Appendix B, §2.6) and accumulation summation.
#include <catch2/catch.hpp>

#include "gaitopt/impact/impact_map.hpp"
#include "gaitopt/impact/solve_impact.hpp"
#include "impact/impact_test_support.hpp"
#include "test_support.hpp"

using namespace gaitopt;

namespace {

ImpactSystem<double> rabbitSystem(const Model& m, const Vec5& q, const Vec2& v2) {
  const test::FloatingState s = test::floatingState(m, q, pinnedVelocityForFoot2(m, q, v2));
  return impactSystem(m, s.X, s.Xd);
}

ImpactOptions withMu(double mu) {
  ImpactOptions o;
  o.mu = mu;
  return o;
}

// The laws every solution must satisfy, checked from its impulses and final velocities with a
// tolerance of 1e-9 relative to |V2⁻| (velocities) and to the impulse scale.
void checkPhysics(const ImpactSystem<double>& sys, const ImpactSolution& s, double mu) {
  const double speed = sys.V_minus.tail<2>().norm();
  const double iscale = speed / sys.W.diagonal().maxCoeff();
  const double tv = 1e-9 * speed, ti = 1e-9 * iscale;
  Eigen::Vector4d I;
  I << s.impulse1, s.impulse2;
  // (2.1) A (Ẋ⁺ − Ẋ⁻) = Dᵀ I, with A⁻¹Dᵀ and W = D A⁻¹ Dᵀ: compare D-space and full velocities
  CHECK((sys.A * (s.Xd_plus - sys.Xd_minus) - sys.A * sys.Ainv_Dt * I).norm() <=
        1e-12 * (1.0 + (sys.A * sys.Ainv_Dt * I).norm()));
  CHECK((s.V_plus - (sys.V_minus + sys.W * I)).norm() <= 1e-12 * (1.0 + speed));
  CHECK(std::abs(s.V_plus(3)) <= tv);  // no bounce
  CHECK(s.impulse2(1) >= -ti);
  CHECK(std::abs(s.impulse2(0)) <= mu * s.impulse2(1) + ti);  // Coulomb cone, foot 2
  CHECK(s.impulse1(1) >= -ti);
  CHECK(std::abs(s.impulse1(0)) <= mu * s.impulse1(1) + ti);
  CHECK(s.V_plus(1) >= -tv);  // foot 1 does not penetrate
  // Kinetic energy never increases.
  const double e_minus = 0.5 * sys.Xd_minus.dot(sys.A * sys.Xd_minus);
  const double e_plus = 0.5 * s.Xd_plus.dot(sys.A * s.Xd_plus);
  CHECK(s.energy_loss == Approx(e_minus - e_plus).margin(1e-12 * e_minus));
  CHECK(e_plus <= e_minus * (1.0 + 1e-12));
}

// The equalities of the behaviour an algebraic solution claims, and its strict-sense signs.
void checkAlgebraicBehaviour(const ImpactSolution& s, double mu, double tv, double ti) {
  const ImpactBehaviour b = s.behaviour;
  if (b.foot1 == Foot1Behaviour::Lift) CHECK(s.impulse1.norm() <= ti);
  if (b.foot1 == Foot1Behaviour::Stick) CHECK(s.V_plus.head<2>().norm() <= tv);
  if (b.foot1 == Foot1Behaviour::SlipPlus) {
    CHECK(s.V_plus(0) >= -tv);
    CHECK(s.impulse1(0) == Approx(-mu * s.impulse1(1)).margin(ti));
  }
  if (b.foot1 == Foot1Behaviour::SlipMinus) {
    CHECK(s.V_plus(0) <= tv);
    CHECK(s.impulse1(0) == Approx(mu * s.impulse1(1)).margin(ti));
  }
  if (b.foot2 == Foot2Behaviour::Stick) CHECK(std::abs(s.V_plus(2)) <= tv);
  if (b.foot2 == Foot2Behaviour::SlipPlus) {
    CHECK(s.V_plus(2) >= -tv);
    CHECK(s.impulse2(0) == Approx(-mu * s.impulse2(1)).margin(ti));
  }
  if (b.foot2 == Foot2Behaviour::SlipMinus) {
    CHECK(s.V_plus(2) <= tv);
    CHECK(s.impulse2(0) == Approx(mu * s.impulse2(1)).margin(ti));
  }
}

// Whether a non-boundary stick–stick (double support) solution is among the solutions.
bool hasDoubleSupport(const ImpactResult& r) {
  for (const ImpactSolution& s : r.solutions)
    if (!s.boundary && s.contact.foot1 == Foot1Behaviour::Stick &&
        s.contact.foot2 == Foot2Behaviour::Stick)
      return true;
  return false;
}

}  // namespace

TEST_CASE("impact solvers: every solution obeys momentum, Coulomb and energy laws", "[impact]") {
  const Model m = test::defaultModel();
  int solutions = 0;
  for (const Vec5& q : {test::walkingImpactQ(m), test::legsSpreadQ(m)})
    for (double mu : {0.2, 0.6, 1.2})
      for (double deg = -175.0; deg < 0.0; deg += 10.0) {
        const double th = deg * M_PI / 180.0;
        const ImpactSystem<double> sys = rabbitSystem(m, q, Vec2(std::cos(th), std::sin(th)));
        const double iscale = 1.0 / sys.W.diagonal().maxCoeff();
        const ImpactResult ra = solveAlgebraicImpact(sys, withMu(mu));
        const ImpactResult rd = solveDifferentialImpact(sys, withMu(mu));
        INFO("mu " << mu << " theta " << deg);
        for (const ImpactSolution& s : ra.solutions) {
          checkPhysics(sys, s, mu);
          checkAlgebraicBehaviour(s, mu, 1e-9, 1e-9 * iscale);
          ++solutions;
        }
        for (const ImpactSolution& s : rd.solutions) {
          checkPhysics(sys, s, mu);
          CHECK(s.phases.back().tau_end == Approx(s.impulse2(1)));  // τ is foot 2's normal impulse
          ++solutions;
        }
        CHECK(ra.status == (ra.solutions.empty()       ? ImpactStatus::Inconsistent
                            : ra.solutions.size() > 1 ? ImpactStatus::Indeterminate
                                                      : ImpactStatus::Unique));
      }
  CHECK(solutions >= 2 * 2 * 3 * 18);  // at least one solution per case and model
}

TEST_CASE("impact solvers: homogeneous in the arriving velocity", "[impact]") {
  const Model m = test::defaultModel();
  const Vec5 q = test::walkingImpactQ(m);
  for (ImpactModelKind kind : {ImpactModelKind::Algebraic, ImpactModelKind::Differential}) {
    const Vec2 v(0.4, -0.7);
    const ImpactResult r1 = solveImpact(m, rabbitSystem(m, q, v).Xd_minus.head<7>().eval() * 0.0 +
                                               test::floatingState(m, q, Vec5::Zero()).X,
                                        rabbitSystem(m, q, v).Xd_minus, kind, withMu(0.5));
    const ImpactResult r3 = solveImpact(m, test::floatingState(m, q, Vec5::Zero()).X,
                                        rabbitSystem(m, q, 3.0 * v).Xd_minus, kind, withMu(0.5));
    REQUIRE(r1.solutions.size() == r3.solutions.size());
    REQUIRE(!r1.solutions.empty());
    for (std::size_t i = 0; i < r1.solutions.size(); ++i) {
      CHECK(r1.solutions[i].behaviour == r3.solutions[i].behaviour);
      CHECK((3.0 * r1.solutions[i].impulse1 - r3.solutions[i].impulse1).norm() <= 1e-10);
      CHECK((3.0 * r1.solutions[i].impulse2 - r3.solutions[i].impulse2).norm() <= 1e-10);
      CHECK(r3.solutions[i].energy_loss == Approx(9.0 * r1.solutions[i].energy_loss));
    }
  }
}

TEST_CASE("impact solvers: a single-phase differential impact equals the algebraic one (2.6)",
          "[impact]") {
  const Model m = test::defaultModel();
  int single = 0;
  for (const Vec5& q : {test::walkingImpactQ(m), test::legsSpreadQ(m)})
    for (double mu : {0.3, 0.8, 1.5})
      for (double deg = -179.0; deg < 0.0; deg += 4.0) {
        const double th = deg * M_PI / 180.0;
        const ImpactSystem<double> sys = rabbitSystem(m, q, Vec2(std::cos(th), std::sin(th)));
        const ImpactResult rd = solveDifferentialImpact(sys, withMu(mu));
        if (rd.solutions.size() != 1 || rd.solutions[0].phases.size() != 1) continue;
        ++single;
        const ImpactSolution& d = rd.solutions[0];
        const ImpactResult ra = solveAlgebraicImpact(sys, withMu(mu));
        bool found = false;
        for (const ImpactSolution& a : ra.solutions)
          if (a.behaviour == d.behaviour) {
            found = true;
            CHECK((a.impulse1 - d.impulse1).norm() <= 1e-10 * (1.0 + d.impulse2.norm()));
            CHECK((a.impulse2 - d.impulse2).norm() <= 1e-10 * (1.0 + d.impulse2.norm()));
            CHECK((a.Xd_plus - d.Xd_plus).norm() <= 1e-10 * (1.0 + d.Xd_plus.norm()));
          }
        INFO("mu " << mu << " theta " << deg << " " << behaviourLabel(d.behaviour));
        CHECK(found);
      }
  CHECK(single >= 20);
}

TEST_CASE("impact solvers: angular momentum about the arriving foot is conserved when foot 1 "
          "lifts", "[impact]") {
  const Model m = test::defaultModel();
  const Vec5 q = test::walkingImpactQ(m);
  const test::FloatingState fs = test::floatingState(m, q, Vec5::Zero());
  const Vec2 foot2 = pinnedTerms(m, q, Vec5(Vec5::Zero())).foot2;
  // Rigid rotation of the whole robot about foot 2: every absolute angle turns (α̇ = 1, the
  // relative angles fixed) and the trunk CoM moves as ω × (X_t − X_2).
  Vector7<double> u = Vector7<double>::Zero();
  u(0) = 1.0;
  u(5) = -(fs.X(6) - foot2(1));
  u(6) = fs.X(5) - foot2(0);
  const FloatingTerms<double> t = floatingTerms(m, fs.X, fs.Xd);
  REQUIRE((t.D2 * u).norm() < 1e-12);  // foot 2 is the rotation centre
  int lifts = 0;
  for (double deg = -170.0; deg < 0.0; deg += 10.0) {
    const double th = deg * M_PI / 180.0;
    const ImpactSystem<double> sys = rabbitSystem(m, q, Vec2(std::cos(th), std::sin(th)));
    for (ImpactModelKind kind : {ImpactModelKind::Algebraic, ImpactModelKind::Differential}) {
      const ImpactResult r = kind == ImpactModelKind::Algebraic
                                 ? solveAlgebraicImpact(sys, withMu(0.8))
                                 : solveDifferentialImpact(sys, withMu(0.8));
      for (const ImpactSolution& s : r.solutions) {
        if (s.impulse1.norm() != 0.0) continue;  // foot 1 lifted through the whole impact
        ++lifts;
        const double sigma_minus = u.dot(sys.A * sys.Xd_minus);  // σ = uᵀ A Ẋ
        const double sigma_plus = u.dot(sys.A * s.Xd_plus);
        CHECK(sigma_plus == Approx(sigma_minus).epsilon(1e-12).margin(1e-12));
      }
    }
  }
  CHECK(lifts >= 10);
}

TEST_CASE("impact solvers: legs spread (2.4.6) need mu of about 0.4 for double support in both "
          "models", "[impact]") {
  const Model m = test::defaultModel();
  const Vec5 q = test::legsSpreadQ(m);
  REQUIRE(q(4) == Approx(-98.8 * M_PI / 180.0).margin(0.01));  // the impacting knee is bent
  // Vertical touchdown (θ = −90°): the only direction where the differential model can end in
  // double support from its first phase (digest §3.3).
  const ImpactSystem<double> sys = rabbitSystem(m, q, Vec2(0.0, -1.0));
  for (ImpactModelKind kind : {ImpactModelKind::Algebraic, ImpactModelKind::Differential}) {
    const auto ds = [&](double mu) {
      return hasDoubleSupport(kind == ImpactModelKind::Algebraic
                                  ? solveAlgebraicImpact(sys, withMu(mu))
                                  : solveDifferentialImpact(sys, withMu(mu)));
    };
    REQUIRE(!ds(0.2));
    REQUIRE(ds(1.0));
    double lo = 0.2, hi = 1.0;
    for (int k = 0; k < 40; ++k) (ds(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
    INFO(toString(kind) << " minimum mu for double support: " << hi);
    CHECK(hi > 0.35);
    CHECK(hi < 0.45);
  }
}

TEST_CASE("impact solvers: Appendix B indeterminacy that Brach's rule hides", "[impact]") {
  Eigen::Matrix4d L;
  L << 0.45109581847598329, 1.7295406265426245, -0.12018748546246935, -0.65435015220248405,
      -0.71586223071017774, -1.6090180144495017, 1.8936184977120036, 0.73171516305627038,
      -1.8608041447667276, -1.0136223917285796, 0.31747368005687404, 1.0761102648517586,
      0.038407228933826643, 0.15415595321276823, -2.3691297906802196, 0.15205742960427363;
  const double mu = 1.2832690374795459;
  const ImpactSystem<double> sys = test::genericSystem(L, -2.6156695080114134);
  const ImpactResult r = solveAlgebraicImpact(sys, withMu(mu));
  CHECK(r.status == ImpactStatus::Indeterminate);
  const ImpactSolution* stick = nullptr;
  const ImpactSolution* slip = nullptr;
  for (const ImpactSolution& s : r.solutions) {
    checkPhysics(sys, s, mu);
    CHECK(!s.boundary);
    if (s.behaviour.foot2 != Foot2Behaviour::Stick) continue;
    if (s.behaviour.foot1 == Foot1Behaviour::Stick) stick = &s;
    if (s.behaviour.foot1 == Foot1Behaviour::SlipPlus || s.behaviour.foot1 == Foot1Behaviour::SlipMinus)
      slip = &s;
  }
  REQUIRE(stick != nullptr);  // "DS without slip"
  REQUIRE(slip != nullptr);   // "DS with rear-foot slip"
  // Brach / Hurmuzlu–Chang (B.2): |μ0| < f at the stick solution → μ = μ0, i.e. only the stick
  // solution; the slip one, which satisfies every law, is dropped.
  const double mu0 = stick->impulse1(0) / stick->impulse1(1);
  CHECK(std::abs(mu0) < mu);
  CHECK(std::abs(slip->V_plus(0)) > 1e-3);  // a genuinely different outcome
}

TEST_CASE("impact solvers: an accumulation of phases is detected and summed", "[impact]") {
  Eigen::Matrix4d L;
  L << 0.85167229062520966, -0.34596288131778308, 0.68213949893979486, -0.44864834909542334,
      -0.058894209621562381, 0.31844461007154479, 0.43738074999646154, -0.37536939312201673,
      -0.97315819576058382, -0.79530768450105782, -1.6847607124713997, 1.0993692143180616,
      1.1429076000271785, 0.027950450178392587, 0.68027518495799533, -0.23627984518538725;
  const double mu = 1.8368830289680642;
  const ImpactSystem<double> sys = test::genericSystem(L, -1.2639283307329889);
  const ImpactResult r = solveDifferentialImpact(sys, withMu(mu));
  const ImpactSolution* acc = nullptr;
  for (const ImpactSolution& s : r.solutions) {
    checkPhysics(sys, s, mu);
    if (s.accumulation) acc = &s;
  }
  REQUIRE(acc != nullptr);
  CHECK(acc->accumulation_cycle_length == 3);
  CHECK(r.status == ImpactStatus::Accumulation);  // every branch ends at the same state
  CHECK(acc->contact.foot1 == Foot1Behaviour::Stick);
  CHECK(acc->contact.foot2 == Foot2Behaviour::Stick);
  // Without summation the same branch creeps toward the accumulation point phase by phase
  // until round-off breaks the pattern: its end must match the summed limit.
  ImpactOptions brute = withMu(mu);
  brute.max_cycle_length = 0;
  brute.max_phases = 20000;
  const ImpactResult rb = solveDifferentialImpact(sys, brute);
  bool matched = false;
  for (const ImpactSolution& s : rb.solutions)
    if (s.phases.size() > 50) {
      matched = true;
      CHECK((s.impulse1 - acc->impulse1).norm() <= 1e-6 * acc->impulse2.norm());
      CHECK((s.impulse2 - acc->impulse2).norm() <= 1e-6 * acc->impulse2.norm());
    }
  CHECK(matched);
  // A capped run never loops forever and says so.
  ImpactOptions capped = brute;
  capped.max_phases = 30;
  bool noted = false;
  for (const std::string& n : solveDifferentialImpact(sys, capped).notes)
    noted = noted || n.find("capped at 30 phases") != std::string::npos;
  CHECK(noted);
}
