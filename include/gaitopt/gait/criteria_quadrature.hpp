#pragma once
// Quadrature of the criteria C_Γ, C_E, W and C_frott (3.28)–(3.32) over the phases: their
// integrands at the phase samples, the Clenshaw–Curtis sums, the kinked integrands split at
// their roots, the DS split into pieces where the force split changes branch, and the SS
// integrals on the finer criteria grid.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "gaitopt/gait/evaluation_context.hpp"
#include "gaitopt/gait/phase_constraints.hpp"
#include "gaitopt/gait/phase_sample.hpp"
#include "gaitopt/gait/zero_dynamics.hpp"
#include "gaitopt/math/bracketed_root.hpp"
#include "gaitopt/math/chebyshev.hpp"
#include "gaitopt/math/chebyshev_abs_integral.hpp"

namespace gaitopt::detail {

// Smooth integrands of the criteria at one sample: Γ*ᵀΓ*, Γ*ᵀω, the electrical power P (3.32)
// and the joint powers Γ*_j ω_j. C_E and W integrate max(0, P) and Σ_j |Γ*_j ω_j| (3.147), whose
// kinks integrateCriteria splits at. The last four are Γ*_j / √|rate|, whose squares sum to
// Γ*ᵀΓ*'s integrand: C_Γ's least-squares residuals (GaitEvaluation::torque_residuals).
constexpr int kTorque2 = 0, kMechanical = 1, kPower = 2, kJointPower = 3, kTorqueRoot = 7,
              kNumIntegrands = 11;
template <class S>
using IntegrandValues = std::array<Eigen::Matrix<S, Eigen::Dynamic, 1>, kNumIntegrands>;

template <class S> IntegrandValues<S> integrandValues(int nodes) {
  IntegrandValues<S> f;
  for (auto& v : f) v.resize(nodes);
  return f;
}

// Integrands at sample k of a phase per unit of its coordinate x (α in the SS, t in the DS):
// per unit time divided by phase_rate = dx/dt (α̇, or 1).
template <class S>
void setIntegrands(const Model& m, const PhaseSample<S>& s, int k, const S& phase_rate,
                   IntegrandValues<S>& f) {
  const S torque2 = s.gamma_star.squaredNorm();
  const S mech = s.gamma_star.dot(s.omega);
  f[kTorque2](k) = torque2 / phase_rate;
  f[kMechanical](k) = mech / phase_rate;
  f[kPower](k) = (mech + jouleCoefficient(m) * torque2) / phase_rate;
  for (int j = 0; j < 4; ++j) f[kJointPower + j](k) = s.gamma_star(j) * s.omega(j) / phase_rate;
  using std::sqrt;
  const S root_rate = sqrt(valueOf(phase_rate) < 0.0 ? S(-phase_rate) : phase_rate);
  for (int j = 0; j < 4; ++j) f[kTorqueRoot + j](k) = s.gamma_star(j) / root_rate;
}

// C_Γ, C_E, W, C_frott (times d) over one smooth piece x ∈ [a, b] of a phase, from the
// integrands per unit x at the grid's nodes mapped to [a, b]. Per unit of the grid coordinate s
// they are f·(b − a)/2, positive for a positive integrand per unit time (in the SS, α and s
// decrease with time and α̇ < 0), hence |b − a|/2 times ∫|f| and ∫max(0, ±f) over s ∈ [−1, 1].
// The kinks of max(0, P) and |Γ*_j ω_j| are appended to `kinks`, in x, in time order.
constexpr int kCriterionCGamma = 0, kCriterionCE = 1, kCriterionW = 2, kCriterionCFrott = 3;

// C_Γ and C_frott: smooth integrands, the Clenshaw–Curtis sum. The Clenshaw–Curtis weights
// are positive, so C_Γ's sum is one of squares: √(w_k |b − a| / 2) Γ*_j / √|rate| at each
// node are appended to `torque_residuals` (Σ r² = this piece's C_Γ · d).
template <class S>
void integrateSmoothCriteria(const ChebyshevGrid& grid, const IntegrandValues<S>& f, const S& a,
                             const S& b, std::array<S, 4>& r, std::vector<S>& torque_residuals) {
  r[kCriterionCGamma] = integrateOverInterval(grid, f[kTorque2], a, b);
  r[kCriterionCFrott] = integrateOverInterval(grid, f[kMechanical], a, b);
  using std::sqrt;
  const S half_length = 0.5 * (valueOf(b) < valueOf(a) ? S(a - b) : S(b - a));
  for (int k = 0; k < grid.size(); ++k) {
    const S root_weight = sqrt(grid.weights()[k] * half_length);
    for (int j = 0; j < 4; ++j) torque_residuals.push_back(root_weight * f[kTorqueRoot + j](k));
  }
}

// C_E and W: the interpolants split at their roots (math/chebyshev_abs_integral.hpp).
template <class S>
void integrateKinkedCriteria(const ChebyshevGrid& grid, const IntegrandValues<S>& f, const S& a,
                             const S& b, std::array<S, 4>& r, std::vector<S>& kinks) {
  const double orientation = valueOf(b) < valueOf(a) ? -1.0 : 1.0;
  const S half_length = 0.5 * orientation * (b - a);
  const Eigen::Matrix<S, Eigen::Dynamic, 1> power = f[kPower] * S(orientation);
  std::vector<S> roots;
  r[kCriterionCE] = half_length * integratePositivePart(grid, power, roots);
  r[kCriterionW] = S(0.0);
  for (int j = 0; j < 4; ++j)
    r[kCriterionW] += half_length * integrateAbs(grid, f[kJointPower + j], roots);
  std::sort(roots.begin(), roots.end(),
            [](const S& x, const S& y) { return valueOf(x) > valueOf(y); });
  for (const S& s : roots) kinks.push_back(a + 0.5 * (1.0 - s) * (b - a));
}

template <class S>
std::array<S, 4> integrateCriteria(const ChebyshevGrid& grid, const IntegrandValues<S>& f,
                                   const S& a, const S& b, std::vector<S>& kinks,
                                   std::vector<S>& torque_residuals) {
  std::array<S, 4> r;
  integrateSmoothCriteria(grid, f, a, b, r, torque_residuals);
  integrateKinkedCriteria(grid, f, a, b, r, kinks);
  return r;
}

// DS pieces: the times where the force-distribution branch changes, from the sign changes of
// its continuous switching functions between grid nodes, and the branch inside each piece. The
// criteria integrands are continuous there, so the switch times carry no derivative (the Leibniz
// terms cancel) and are plain doubles.
template <class S>
DsPieces dsPieces(EvalContext<S>& c, const Eigen::Matrix<S, Eigen::Dynamic, 1>& ts,
                  const std::vector<int>& branch,
                  const std::vector<std::array<double, 6>>& switching) {
  const auto phi = [&c](double t, int i) {
    return valueOf(dsSample(c.model, c.options, c.out.motion, S(t)).switching[i]);
  };
  std::vector<std::pair<double, int>> found;
  for (std::size_t k = 0; k + 1 < switching.size(); ++k)
    for (int i = 0; i < 6 && branch[k] != branch[k + 1]; ++i) {
      const double a = switching[k][i], b = switching[k + 1][i];
      if ((a < 0.0) == (b < 0.0)) continue;
      const auto fn = [&phi, i](double t) { return phi(t, i); };
      found.push_back({bracketedRoot(fn, valueOf(ts(k)), a, valueOf(ts(k + 1)), b), i});
    }
  std::sort(found.begin(), found.end());
  DsPieces pieces;
  const double h = 1e-7 * valueOf(c.out.motion.T_DS);
  for (const auto& [t, i] : found) {
    pieces.switch_times.push_back(t);
    pieces.switch_function.push_back(i);
    const double rate = (phi(t + h, i) - phi(t - h, i)) / (2.0 * h);
    pieces.switch_rate.push_back(std::isfinite(rate) ? rate : 0.0);
  }
  const double T = valueOf(c.out.motion.T_DS);
  for (std::size_t i = 0; i <= found.size(); ++i) {
    const double a = i == 0 ? 0.0 : found[i - 1].first;
    const double b = i == found.size() ? T : found[i].first;
    pieces.branches.push_back(dsSample(c.model, c.options, c.out.motion, S(0.5 * (a + b))).branch);
  }
  return pieces;
}

// A switch time with its parameter derivative from φ(t_s(p), p) = 0 (implicit function
// theorem, as (3.146)): one Newton step from the located root, on the AD scalar.
template <class S> S switchTimeWithDerivative(EvalContext<S>& c, const DsPieces& pieces, int j) {
  const double t = pieces.switch_times[j];
  if (pieces.switch_rate[j] == 0.0) return S(t);  // no usable rate: the switch stays put
  const S phi = dsSample(c.model, c.options, c.out.motion, S(t), pieces.branches[j])
                    .switching[pieces.switch_function[j]];
  return S(t) - phi / pieces.switch_rate[j];
}

// The DS level-5 entries of sample k of a piece, with the piece's branch, so that the
// constraints can be held between the DS nodes on smooth pieces (GaitEvaluation::ds_piece_g),
// and the joint speeds there (GaitEvaluation::ds_piece_speeds).
template <class S>
void recordPieceSample(EvalContext<S>& c, const std::vector<S>& ends, std::size_t piece, int k,
                       const PhaseSample<S>& s) {
  std::vector<std::vector<S>>& g = c.out.ds_piece_g;
  if (g.empty()) {
    g.assign(ends.size() + 1, std::vector<S>(c.layout.dsMotionSize()));
    c.out.ds_piece_speeds.assign(ends.size() + 1, std::vector<S>(4 * c.piece_grid.size()));
    c.out.ds_piece_bounds = {0.0};
    for (const S& t : ends) c.out.ds_piece_bounds.push_back(valueOf(t));
    c.out.ds_piece_bounds.push_back(valueOf(c.out.motion.T_DS));
  }
  std::vector<S>& v = g[piece];
  for (int j = 0; j < 4; ++j) c.out.ds_piece_speeds[piece][4 * k + j] = s.omega(j);
  const int first = c.layout.dsMotionOffset();
  dsConstraintValues(c, k, s, [&c, &v, first](int group, int index, const S& value) {
    v[c.layout[group].offset + index - first] = value;
  });
}

template <class S>
std::array<S, 4> integrateDsPiecewise(EvalContext<S>& c, const DsPieces& pieces) {
  const GaitMotion<S>& mo = c.out.motion;
  const std::vector<double>& sw = pieces.switch_times;
  std::array<S, 4> total{S(0.0), S(0.0), S(0.0), S(0.0)};
  IntegrandValues<S> f = integrandValues<S>(c.piece_grid.size());
  std::vector<S> ends;
  for (std::size_t j = 0; j < sw.size(); ++j)
    ends.push_back(switchTimeWithDerivative(c, pieces, static_cast<int>(j)));
  for (std::size_t piece = 0; piece <= sw.size(); ++piece) {
    const S a = piece == 0 ? S(0.0) : ends[piece - 1];
    const S b = piece == sw.size() ? mo.T_DS : ends[piece];
    const auto ts = mappedNodes(c.piece_grid, a, b);
    for (int k = 0; k < c.piece_grid.size(); ++k) {
      const PhaseSample<S> s = dsSample(c.model, c.options, mo, S(ts(k)), pieces.branches[piece]);
      setIntegrands(c.model, s, k, S(1.0), f);
      if (c.record_pieces) recordPieceSample(c, ends, piece, k, s);
    }
    const std::array<S, 4> part =
        integrateCriteria(c.piece_grid, f, a, b, c.out.criteria_kinks, c.out.torque_residuals);
    for (int i = 0; i < 4; ++i) total[i] += part[i];
  }
  return total;
}

// The SS integrals of the criteria. W and C_E integrate |Γ*_j ω_j| and max(0, P) split at their
// roots, i.e. the integrands' interpolant between the nodes, which on the SS grid is accurate
// to ~10⁻⁹ only (a Clenshaw–Curtis sum, as for C_Γ, is exact far beyond its interpolant): they
// are sampled on the nested grid GaitGrids::ss_criteria (every r-th node an SS node, whose path
// point is reused) with Φ (3.14) integrated on that grid. C_Γ and C_frott keep the SS grid.
template <class S>
std::array<S, 4> ssCriteria(EvalContext<S>& c, const std::vector<SsPathPoint<S>>& pts,
                            const IntegrandValues<S>& ss_int) {
  const GaitMotion<S>& mo = c.out.motion;
  const S& a = mo.alpha_iSS;
  const S& b = mo.alpha_fSS;
  std::array<S, 4> r;
  integrateSmoothCriteria(c.ss_grid, ss_int, a, b, r, c.out.torque_residuals);
  const ChebyshevGrid& fine = c.ss_criteria_grid;
  const int refinement = fine.degree() / c.ss_grid.degree();
  if (refinement == 1) {
    integrateKinkedCriteria(c.ss_grid, ss_int, a, b, r, c.out.criteria_kinks);
    return r;
  }
  const auto alphas = mappedNodes(fine, a, b);
  std::vector<SsPathPoint<S>> added;
  added.reserve(fine.size() - pts.size());
  for (int k = 0; k < fine.size(); ++k)
    if (k % refinement != 0) added.push_back(ssPathPoint(c.model, mo, S(alphas(k))));
  const auto point = [&](int k) -> const SsPathPoint<S>& {
    return k % refinement == 0 ? pts[k / refinement] : added[k - k / refinement - 1];
  };
  const double f_min = c.options.f_min;
  Eigen::Matrix<S, Eigen::Dynamic, 1> dphi(fine.size());
  for (int k = 0; k < fine.size(); ++k) dphi(k) = phiRate(point(k), f_min);
  const auto phi = cumulativeOverInterval(fine, dphi, a, b);
  IntegrandValues<S> f = integrandValues<S>(fine.size());
  for (int k = 0; k < fine.size(); ++k) {
    S ad, add;
    zeroDynamicsRates(point(k), phi(k), mo, f_min, ad, add);
    setIntegrands(c.model, ssSample(c.model, point(k), ad, add), k, ad, f);
  }
  integrateKinkedCriteria(fine, f, a, b, r, c.out.criteria_kinks);
  return r;
}

}  // namespace gaitopt::detail
