#pragma once
// Pointwise solution of the double-support redundancy in R2x (§3.3.3): Γ* = J − K R2x, ground
// bounds R_inf ≤ R2x ≤ R_sup from the friction cones of both feet ((3.63)–(3.66), corrected),
// minimum of the torque norm (3.68) or of the electrical power (3.71)–(3.75), midpoint (3.70)
// when no feasible R2x exists. Continuous in time by construction.
#include <array>
#include <cmath>

#include "gaitopt/math/scalar.hpp"
#include "gaitopt/math/types.hpp"

namespace gaitopt {

template <class S> struct DsBounds {
  S lower, upper;
  int active = 0;  // which cone rows give the bounds: bit 0 lower, bit 1 upper
  S lower_gap, upper_gap;  // differences of the two candidates of each bound
};

// Which formula produced R2x, encoded 4·mode + active bounds (mode 0 optimum, 1 lower bound,
// 2 upper bound, 3 infeasible midpoint, 4–6 zero-power interval of the energy case). The
// integrand of the criteria has a kink wherever it changes, so phase integrals are split there,
// and every sample of one piece is computed with that piece's branch (kBranchFree: choose).
constexpr int kBranchFree = -1;

template <class S> struct DsChoice {
  S r2x;
  int branch;
  // Continuous functions whose sign changes are the branch changes: unconstrained optimum
  // minus each bound, the two candidates of each bound, and the power at the clamped optimum.
  std::array<S, 6> switching{};
};

// Explicit (3.66): R_sup = min(f R1z + M ẍ_G, f R2z), R_inf = max(−f R1z + M ẍ_G, −f R2z).
template <class S>
DsBounds<S> r2xBounds(const S& R1z, const S& R2z, const S& m_xddG, double f, int forced) {
  const S a = f * R1z + m_xddG, b = f * R2z;
  const S c = -f * R1z + m_xddG, e = -f * R2z;
  const bool lower_foot2 = forced >= 0 ? (forced & 1) != 0 : valueOf(e) >= valueOf(c);
  const bool upper_foot2 = forced >= 0 ? (forced & 2) != 0 : valueOf(b) <= valueOf(a);
  return {lower_foot2 ? e : c, upper_foot2 ? b : a, (lower_foot2 ? 1 : 0) | (upper_foot2 ? 2 : 0),
          S(e - c), S(b - a)};
}

template <class S>
DsChoice<S> clampTo(const S& x, const S& lo, const S& hi, int forced_mode) {
  const int mode = forced_mode >= 0 ? forced_mode
                   : valueOf(x) < valueOf(lo) ? 1
                   : valueOf(x) > valueOf(hi) ? 2
                                              : 0;
  return {mode == 1 ? lo : mode == 2 ? hi : x, mode};
}

template <class S>
DsChoice<S> withBounds(DsChoice<S> c, const DsBounds<S>& b, const S& optimum) {
  c.branch = 4 * c.branch + b.active;
  c.switching = {S(optimum - b.lower), S(optimum - b.upper), b.lower_gap, b.upper_gap,
                 S(b.lower - b.upper), S(0.0)};
  return c;
}

inline int forcedMode(int branch) { return branch < 0 ? kBranchFree : branch / 4; }

template <class S> bool infeasibleBounds(const DsBounds<S>& b, int forced_mode) {
  return forced_mode >= 0 ? forced_mode == 3 : valueOf(b.lower) > valueOf(b.upper);
}

// (3.68)–(3.70).
template <class S>
DsChoice<S> r2xMinTorque(const Vector4<S>& J, const Vector4<S>& K, const DsBounds<S>& b,
                         int forced_branch) {
  const int mode = forcedMode(forced_branch);
  const S optimum = K.dot(J) / K.squaredNorm();
  if (infeasibleBounds(b, mode)) return withBounds<S>({0.5 * (b.lower + b.upper), 3}, b, optimum);
  return withBounds(clampTo(optimum, b.lower, b.upper, mode), b, optimum);
}

// (3.71)–(3.75) with P(R) = c − bR + aR², joule coefficient k = R/(N K_em)² (digest gap #5).
template <class S>
DsChoice<S> r2xMinPower(const Vector4<S>& J, const Vector4<S>& K, const Vector4<S>& omega,
                        double k, const DsBounds<S>& bounds, int forced_branch) {
  using std::sqrt;
  const int mode = forcedMode(forced_branch);
  const S mid = 0.5 * (bounds.lower + bounds.upper);
  const S a = k * K.squaredNorm();
  const S b = omega.dot(K) + 2.0 * k * J.dot(K);
  const S c = omega.dot(J) + k * J.squaredNorm();
  const S optimum = b / (2.0 * a);
  if (infeasibleBounds(bounds, mode)) return withBounds<S>({mid, 3}, bounds, optimum);
  DsChoice<S> r = clampTo(optimum, bounds.lower, bounds.upper, mode >= 4 ? kBranchFree : mode);
  const S power = c - b * r.r2x + a * r.r2x * r.r2x;
  if (mode >= 4 || (mode < 0 && valueOf(power) < 0.0)) {
    // P < 0 somewhere: any R with P ≤ 0 costs nothing; keep the one deepest inside the bounds.
    const S disc = sqrt(b * b - 4.0 * a * c);
    r = clampTo(mid, S((b - disc) / (2.0 * a)), S((b + disc) / (2.0 * a)),
                mode >= 4 ? mode - 4 : kBranchFree);
    r.branch += 4;
  }
  r = withBounds(r, bounds, optimum);
  r.switching[5] = power;
  return r;
}

}  // namespace gaitopt
