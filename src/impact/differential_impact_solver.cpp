// Differential impact (Keller; Hurmuzlu–Marghitu) as a sequence of algebraic phases in the
// normal impulse τ of foot 2 (§2.3–2.5, Table 2.1). Within a phase the rates ΔI, ΔV are
// constant (2.39)–(2.40) and depend only on the behaviour, so each phase is linear in its
// start velocities: a repeated phase pattern is a linear map, and an infinite repetition
// (accumulation) is summed as a geometric series.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gaitopt/impact/solve_impact.hpp"

namespace gaitopt {
namespace {

using Vec4d = Eigen::Vector4d;
using Mat4d = Eigen::Matrix4d;
using RowVec4d = Eigen::RowVector4d;

// Contact-space indices of V and I.
constexpr int kX1 = 0, kZ1 = 1, kX2 = 2, kZ2 = 3;

struct PhaseRates {
  ImpactBehaviour behaviour;
  Vec4d dI, dV;  // per unit of τ; dI(kZ2) = 1
  bool boundary = false;
};

// One completed phase, kept for accumulation detection: its rates and the velocity component
// whose zero ended it.
struct PhaseRecord {
  PhaseRates rates;
  int event;
};

struct Branch {
  Vec4d V, I = Vec4d::Zero();
  double tau = 0.0;
  std::vector<ImpactPhase> phases;
  std::vector<PhaseRecord> history;  // since the last summed accumulation
  bool boundary = false;
  int accumulation_cycle = 0;
};

class DifferentialSolver {
 public:
  DifferentialSolver(const ImpactSystem<double>& system, const ImpactOptions& options)
      : sys_(system), opt_(options), scale_(detail::impactScales(system)),
        eps_v_(options.tolerance * scale_.speed),
        w_scale_(system.W.diagonal().maxCoeff()) {}

  ImpactResult run() {
    ImpactResult result;
    result.model = ImpactModelKind::Differential;
    result.mu = opt_.mu;
    result.V2_minus = sys_.V_minus.tail<2>();
    Branch start;
    start.V = sys_.V_minus;
    start.V(kX1) = start.V(kZ1) = 0.0;  // V1⁻ = 0 (C.1): foot 1 at rest before the impact
    std::vector<Branch> open{start};
    int branches = 1;
    while (!open.empty()) {
      Branch b = std::move(open.back());
      open.pop_back();
      advance(std::move(b), open, branches, result);
    }
    result.status = detail::statusOf(result.solutions, opt_.tolerance * scale_.impulse,
                                   opt_.outcome_tolerance);
    return result;
  }

 private:
  bool atRest(double v) const { return std::abs(v) <= eps_v_; }

  // Admissible behaviours from the start-of-phase state (Table 2.1).
  std::vector<ImpactBehaviour> admissible(const Vec4d& V) const {
    std::vector<Foot1Behaviour> f1{Foot1Behaviour::Lift};
    if (atRest(V(kZ1))) {
      if (atRest(V(kX1)))
        f1.insert(f1.end(),
                  {Foot1Behaviour::Stick, Foot1Behaviour::SlipPlus, Foot1Behaviour::SlipMinus});
      else
        f1.push_back(V(kX1) > 0.0 ? Foot1Behaviour::SlipPlus : Foot1Behaviour::SlipMinus);
    }
    std::vector<Foot2Behaviour> f2;
    if (atRest(V(kX2)))
      f2 = {Foot2Behaviour::Stick, Foot2Behaviour::SlipPlus, Foot2Behaviour::SlipMinus};
    else
      f2 = {V(kX2) > 0.0 ? Foot2Behaviour::SlipPlus : Foot2Behaviour::SlipMinus};
    std::vector<ImpactBehaviour> out;
    for (Foot1Behaviour a : f1)
      for (Foot2Behaviour c : f2) out.push_back({a, c});
    return out;
  }

  // The three unknown rates u = [ΔI1x, ΔI1z, ΔI2x] from the behaviour's equalities, with
  // ΔI2z = 1 (2.40). Returns false when the equality set is singular.
  bool rates(ImpactBehaviour b, PhaseRates& r) const {
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    const auto velocityRow = [&](int k, int row) {  // ΔV_k = 0
      M.row(row) = sys_.W.row(k).head<3>();
      rhs(row) = -sys_.W(k, kZ2);
    };
    const double mu = opt_.mu;
    switch (b.foot1) {
      case Foot1Behaviour::Lift: M(0, 0) = M(1, 1) = 1.0; break;  // ΔI1 = 0 (2.41)
      case Foot1Behaviour::Stick: velocityRow(kX1, 0); velocityRow(kZ1, 1); break;  // (2.42)
      case Foot1Behaviour::SlipPlus:  // ΔV1z = 0, ΔI1x = ∓μ ΔI1z (2.43)
      case Foot1Behaviour::SlipMinus:
        velocityRow(kZ1, 0);
        M(1, 0) = 1.0;
        M(1, 1) = b.foot1 == Foot1Behaviour::SlipPlus ? mu : -mu;
        break;
    }
    switch (b.foot2) {
      case Foot2Behaviour::Stick: velocityRow(kX2, 2); break;  // ΔV2x = 0 (2.44)
      case Foot2Behaviour::SlipPlus: M(2, 2) = 1.0; rhs(2) = -mu; break;  // (2.45)
      case Foot2Behaviour::SlipMinus: M(2, 2) = 1.0; rhs(2) = mu; break;
    }
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(M);
    if (!lu.isInvertible()) return false;
    const Eigen::Vector3d u = lu.solve(rhs);
    r.behaviour = b;
    r.dI << u, 1.0;
    r.dV = sys_.W * r.dI;
    return true;
  }

  // Conditions (2.41)–(2.45) as dimensionless slacks; false when one is violated.
  bool consistent(const Vec4d& V, PhaseRates& r) const {
    std::vector<double> slacks;  // impulse rates are dimensionless; velocity rates / max W_ii
    const double mu = opt_.mu;
    const Vec4d dv = r.dV / w_scale_;
    const Vec4d& di = r.dI;
    switch (r.behaviour.foot1) {
      case Foot1Behaviour::Lift:
        if (atRest(V(kZ1))) slacks.push_back(dv(kZ1));  // leaving the ground
        break;
      case Foot1Behaviour::Stick:
        slacks.insert(slacks.end(), {mu * di(kZ1) - di(kX1), mu * di(kZ1) + di(kX1), di(kZ1)});
        break;
      case Foot1Behaviour::SlipPlus:
      case Foot1Behaviour::SlipMinus: {
        slacks.push_back(di(kZ1));
        const double dir = r.behaviour.foot1 == Foot1Behaviour::SlipPlus ? 1.0 : -1.0;
        if (atRest(V(kX1))) slacks.push_back(dir * dv(kX1));  // slip from rest (2.43)
        break;
      }
    }
    switch (r.behaviour.foot2) {
      case Foot2Behaviour::Stick: slacks.insert(slacks.end(), {mu - di(kX2), mu + di(kX2)}); break;
      case Foot2Behaviour::SlipPlus:
        if (atRest(V(kX2))) slacks.push_back(dv(kX2));
        break;
      case Foot2Behaviour::SlipMinus:
        if (atRest(V(kX2))) slacks.push_back(-dv(kX2));
        break;
    }
    for (double s : slacks) {
      if (s < -opt_.tolerance) return false;
      r.boundary = r.boundary || std::abs(s) <= opt_.tolerance;
    }
    return true;
  }

  // End of phase (2.46)–(2.47): the smallest positive Δτ at which a velocity that was
  // non-zero at the start reaches 0. Returns the event components (ties within tolerance).
  std::vector<int> events(const Vec4d& V, const PhaseRates& r, double& dtau) const {
    std::vector<std::pair<double, int>> c;
    const auto candidate = [&](int k) {
      if (!atRest(V(k)) && V(k) * r.dV(k) < 0.0) c.push_back({-V(k) / r.dV(k), k});
    };
    candidate(kZ2);                                               // end of impact (2.29)
    candidate(kX2);                                               // foot 2 slip end (2.27)
    if (r.behaviour.foot1 == Foot1Behaviour::Lift) candidate(kZ1);  // lift end (2.28)
    else candidate(kX1);                                            // foot 1 slip end (2.27)
    std::vector<int> out;
    if (c.empty()) return out;
    dtau = std::min_element(c.begin(), c.end())->first;
    for (const auto& [t, k] : c)
      if (t <= dtau * (1.0 + opt_.tolerance)) out.push_back(k);
    return out;
  }

  enum class StepEnd { ImpactEnded, NextPhase, NeverEnds };

  void advance(Branch b, std::vector<Branch>& open, int& branches, ImpactResult& result) {
    while (static_cast<int>(b.phases.size()) < opt_.max_phases) {
      std::vector<PhaseRates> ok;
      for (ImpactBehaviour beh : admissible(b.V)) {
        PhaseRates r;
        if (rates(beh, r) && consistent(b.V, r)) ok.push_back(r);
      }
      if (ok.empty()) {
        result.notes.push_back("phase " + std::to_string(b.phases.size() + 1) +
                               ": no consistent behaviour (inconsistency)");
        return;
      }
      for (std::size_t k = 1; k < ok.size(); ++k) {  // indeterminate phase: branch
        if (branches >= opt_.max_branches) {
          result.notes.push_back("branch limit reached; further branches not explored");
          break;
        }
        ++branches;
        Branch other = b;
        const StepEnd end = step(other, ok[k], result);
        if (end == StepEnd::ImpactEnded) finish(other, result);
        if (end == StepEnd::NextPhase) open.push_back(std::move(other));
      }
      const StepEnd end = step(b, ok.front(), result);
      if (end == StepEnd::ImpactEnded) return finish(b, result);
      if (end == StepEnd::NeverEnds) return;
      sumAccumulation(b);
    }
    result.notes.push_back("phase sequence capped at " + std::to_string(opt_.max_phases) +
                           " phases without ending the impact");
  }

  // Runs one phase of behaviour r.
  StepEnd step(Branch& b, const PhaseRates& r, ImpactResult& result) {
    double dtau = 0.0;
    const std::vector<int> ev = events(b.V, r, dtau);
    if (ev.empty()) {
      result.notes.push_back("phase " + std::to_string(b.phases.size() + 1) + " (" +
                             toString(r.behaviour.foot1) + "/" + toString(r.behaviour.foot2) +
                             "): no end event, the impact never ends (inconsistency)");
      return StepEnd::NeverEnds;
    }
    b.V += r.dV * dtau;
    b.I += r.dI * dtau;
    b.tau += dtau;
    for (int k : ev) b.V(k) = 0.0;  // the event's component is 0 by definition
    b.boundary = b.boundary || r.boundary;
    b.phases.push_back({r.behaviour, b.tau});
    b.history.push_back({r, ev.front()});
    return std::find(ev.begin(), ev.end(), kZ2) != ev.end() ? StepEnd::ImpactEnded
                                                          : StepEnd::NextPhase;
  }

  // When the last p phases repeat the p before them (same behaviours, same ending events), the
  // pattern is a linear map V ↦ M V with impulses N V and τ-increment g V per cycle; its
  // infinite repetition is summed (M^m and Σ_{n<m} M^n by doubling m) and the branch jumps to
  // the accumulation point.
  void sumAccumulation(Branch& b) {
    const std::size_t n = b.history.size();
    for (int p = 1; p <= opt_.max_cycle_length; ++p) {
      const std::size_t up = static_cast<std::size_t>(p);
      if (n < 2 * up) return;
      bool same = true;
      for (std::size_t j = 0; j < up && same; ++j) {
        const PhaseRecord& a = b.history[n - 1 - j];
        const PhaseRecord& c = b.history[n - 1 - j - up];
        same = a.rates.behaviour == c.rates.behaviour && a.event == c.event;
      }
      if (same && sumCycle(b, n - up, up)) {
        b.accumulation_cycle = p;
        b.history.clear();
        return;
      }
    }
  }

  bool sumCycle(Branch& b, std::size_t first, std::size_t length) {
    Mat4d M = Mat4d::Identity(), N = Mat4d::Zero();
    RowVec4d g = RowVec4d::Zero();
    for (std::size_t j = first; j < first + length; ++j) {
      const PhaseRecord& rec = b.history[j];
      const RowVec4d c = -RowVec4d::Unit(rec.event) / rec.rates.dV(rec.event);  // Δτ = c V
      N += rec.rates.dI * (c * M);
      g += c * M;
      M = (Mat4d::Identity() + rec.rates.dV * c) * M;
    }
    Mat4d P = M, S = Mat4d::Identity();  // P = M^m, S = Σ_{n<m} M^n with m = 1
    for (int k = 0; k < 60; ++k) {
      const Mat4d P2 = P * P;
      S += P * S;
      const bool converged = (P2 - P).norm() <= 1e-14 * (1.0 + P.norm());
      P = P2;
      if (!P.allFinite() || P.norm() > 1e12) return false;  // not contracting: no limit
      if (converged) {
        const Vec4d delta = (Mat4d::Identity() - P) * b.V;  // the part that dies out
        b.I += N * (S * delta);
        b.tau += g * (S * delta);
        b.V = P * b.V;
        for (std::size_t j = first; j < first + length; ++j) b.V(b.history[j].event) = 0.0;
        b.phases.push_back({b.phases.back().behaviour, b.tau});
        return true;
      }
    }
    return false;
  }

  void finish(const Branch& b, ImpactResult& result) const {
    ImpactSolution s;
    s.behaviour = b.phases.back().behaviour;
    s.boundary = b.boundary;
    s.phases = b.phases;
    s.accumulation = b.accumulation_cycle > 0;
    s.accumulation_cycle_length = b.accumulation_cycle;
    detail::completeSolution(sys_, b.I, opt_, s);
    result.solutions.push_back(std::move(s));  // every branch is reported (statusOf counts outcomes)
  }

  const ImpactSystem<double>& sys_;
  const ImpactOptions& opt_;
  detail::ImpactScales scale_;
  double eps_v_, w_scale_;
};

}  // namespace

ImpactResult solveDifferentialImpact(const ImpactSystem<double>& system,
                                     const ImpactOptions& options) {
  return DifferentialSolver(system, options).run();
}

}  // namespace gaitopt
