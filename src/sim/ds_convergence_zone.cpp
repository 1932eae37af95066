#include "gaitopt/sim/ds_convergence_zone.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "gaitopt/sim/cvode_integrator.hpp"

namespace gaitopt {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double alphaIDS(const GaitMotion<double>& mo) { return mo.ds_alpha(0.0).value; }
double alphaFDS(const GaitMotion<double>& mo) { return mo.ds_alpha(mo.T_DS).value; }

// Width [rad/s²] of the admissible α̈ interval below which (4.2) counts as infeasible (H1
// fails): the interval shrinks to a point there, and this event stops a curve just before it
// (past it the bounds do not exist and CVODE's steps would shrink without end).
constexpr double kMinAdmissibleWidth = 1e-6;

// α̈ of a law at (α, α̇) and the width α̈_max − α̈_min of the admissible interval there (NaN
// where (4.2) is infeasible).
struct LawValue {
  double alphadd, width;
};
using AlphaLaw = std::function<LawValue(double alpha, double alphad)>;
// Event function of (α, v) falling through 0, or none.
using AlphaEvent = std::function<double(double alpha, double v)>;

struct Integrated {
  DsPhaseCurve curve;
  int root = -1;  // 0: α̇ = 0, 1: the extra event, 2: (4.2) infeasible, −1: the target α
  bool failed = false;  // CVODE failed (reported as (4.2) infeasible)
};

// v = α̇² over σ ∈ [0, 1], α = α0 + σ (α1 − α0): dv/dσ = 2 α̈ (α1 − α0); samples at equal σ.
Integrated integrateAlpha(double alpha0, double alpha1, double alphad0, const AlphaLaw& law,
                          const AlphaEvent& event, int samples) {
  const double span = alpha1 - alpha0;
  const auto alphaAt = [&](double s) { return alpha0 + s * span; };
  const auto alphadOf = [](double v) { return -std::sqrt(std::max(v, 0.0)); };  // H2
  CvodeIntegrator cv(
      1,
      [&](double s, const Eigen::VectorXd& y, Eigen::VectorXd& f) {
        f.resize(1);
        f(0) = 2.0 * law(alphaAt(s), alphadOf(y(0))).alphadd * span;
      },
      3,
      [&](double s, const Eigen::VectorXd& y, Eigen::VectorXd& g) {
        const double width = law(alphaAt(s), alphadOf(y(0))).width;
        g.resize(3);
        g << y(0), event ? event(alphaAt(s), y(0)) : 1.0,
            std::isnan(width) ? -1.0 : width - kMinAdmissibleWidth;
      });
  Eigen::VectorXd y(1);
  y << alphad0 * alphad0;
  cv.reset(0.0, y);
  Integrated out;
  out.curve.alpha.push_back(alpha0);
  out.curve.alphad.push_back(alphad0);
  for (int k = 1; k < samples; ++k) {
    CvodeIntegrator::Result r;
    try {
      r = cv.advance(static_cast<double>(k) / (samples - 1));
    } catch (const std::runtime_error&) {
      out.failed = true;
      break;
    }
    out.curve.alpha.push_back(alphaAt(r.t));
    out.curve.alphad.push_back(r.root == 0 ? 0.0 : alphadOf(r.y(0)));
    if (r.root >= 0) {
      out.root = r.root;
      break;
    }
  }
  out.curve.end_alphad = out.curve.alphad.back();
  return out;
}

double interpolate(const DsPhaseCurve& c, double alpha) {
  for (std::size_t i = 1; i < c.alpha.size(); ++i) {
    const double a = c.alpha[i - 1], b = c.alpha[i];
    if ((alpha - a) * (alpha - b) <= 0.0)
      return a == b ? c.alphad[i] : c.alphad[i - 1] + (alpha - a) / (b - a) * (c.alphad[i] - c.alphad[i - 1]);
  }
  // A curve integrated up to α (its end) may stop a rounding error short of it.
  const double tolerance = 1e-12 * std::max(1.0, std::abs(alpha));
  if (!c.alpha.empty() && std::abs(alpha - c.alpha.back()) <= tolerance) return c.alphad.back();
  return kNaN;
}

AlphaLaw boundLaw(const Model& m, const GaitMotion<double>& mo, const DsLimits& l, bool braking) {
  return [&m, &mo, l, braking](double alpha, double alphad) {
    const DsAccelerationBounds b = dsAccelerationBounds(m, mo, l, alpha, alphad);
    const double a = braking ? b.max : b.min;
    if (!b.defined || !std::isfinite(a)) return LawValue{kNaN, kNaN};  // H1
    return LawValue{a, b.max - b.min};
  };
}

// The rest of a curve that met the cyclic curve at its last sample: along α̇_c(α) to α_fDS.
void followCycle(const GaitMotion<double>& mo, double alpha_end, int samples, DsPhaseCurve& c) {
  const double a0 = c.alpha.back();
  const int n = std::max(2, samples - static_cast<int>(c.alpha.size()) + 1);
  for (int k = 1; k < n; ++k) {
    const double alpha = a0 + (alpha_end - a0) * k / (n - 1);
    c.alpha.push_back(alpha);
    c.alphad.push_back(cyclicDsAlpha(mo, alpha).alphad);
  }
  c.end = "on_cycle";
  c.end_alphad = c.alphad.back();
}

}  // namespace

DsPhaseCurve dsBoundCurve(const Model& m, const GaitMotion<double>& mo, const DsLimits& l,
                          double alphad_fDS, DsBoundKind kind, int samples) {
  Integrated r = integrateAlpha(alphaFDS(mo), alphaIDS(mo), alphad_fDS,
                                boundLaw(m, mo, l, kind == DsBoundKind::Braking), nullptr, samples);
  r.curve.end = r.failed || r.root == 2 ? "undefined" : r.root == 0 ? "at_rest" : "alpha_iDS";
  return r.curve;
}

double DsConvergenceZone::fastest(double alpha) const { return interpolate(braking, alpha); }

double DsConvergenceZone::slowest(double alpha) const {
  const double v = interpolate(speeding_up, alpha);
  return std::isnan(v) && speeding_up.end == "at_rest" ? 0.0 : v;
}

bool DsConvergenceZone::contains(double alpha, double alphad) const {
  return alphad <= 0.0 && fastest(alpha) <= alphad && alphad <= slowest(alpha);
}

DsConvergenceZone dsConvergenceZone(const Model& m, const GaitMotion<double>& mo,
                                    const DsLimits& l, double alphad_fDS, int samples) {
  return {alphad_fDS, dsBoundCurve(m, mo, l, alphad_fDS, DsBoundKind::Braking, samples),
          dsBoundCurve(m, mo, l, alphad_fDS, DsBoundKind::SpeedingUp, samples)};
}

DsPhaseCurve runTimeOptimalDs(const Model& m, const GaitMotion<double>& mo, const DsLimits& l,
                              double alpha_start, double alphad_start, int samples) {
  const double alpha_end = alphaFDS(mo);
  const double gap = alphad_start - cyclicDsAlpha(mo, alpha_start).alphad;
  DsPhaseCurve c;
  if (std::abs(gap) <= 1e-12 * std::abs(alphad_start)) {  // on the curve already
    c.alpha.push_back(alpha_start);
    c.alphad.push_back(alphad_start);
    followCycle(mo, alpha_end, samples, c);
    return c;
  }
  const bool too_fast = gap < 0.0;  // α̇ < α̇_c < 0: brake with α̈_max (4.1)
  const AlphaEvent meet = [&mo, too_fast](double alpha, double v) {
    const double vc = std::pow(cyclicDsAlpha(mo, alpha).alphad, 2);
    return too_fast ? v - vc : vc - v;
  };
  Integrated r = integrateAlpha(alpha_start, alpha_end, alphad_start,
                                boundLaw(m, mo, l, too_fast), meet, samples);
  if (r.root == 1) {
    followCycle(mo, alpha_end, samples, r.curve);
    return r.curve;
  }
  r.curve.end = r.failed || r.root == 2 ? "undefined" : r.root == 0 ? "at_rest" : "alpha_fDS";
  return r.curve;
}

double zeroDynamicsStepMap(const GaitMotion<double>& mo, double alphad_fDS) {
  const Eigen::Index n = mo.ss_phi.size();
  const double fi2 = mo.f_iSS * mo.f_iSS;
  // f(α_fSS) from the gait's own cycle: α̇_fSS = −√(Φ_f + f_i² α̇_iSS²) / f_f.
  const double f_f = -std::sqrt(mo.ss_phi(n - 1) + fi2 * mo.alphadot_iSS * mo.alphadot_iSS) /
                     mo.alphadot_fSS;
  for (Eigen::Index k = 0; k < n; ++k)
    if (mo.ss_phi(k) + fi2 * alphad_fDS * alphad_fDS <= 0.0) return kNaN;  // falls back (3.55)
  return -mo.kappa * std::sqrt(mo.ss_phi(n - 1) + fi2 * alphad_fDS * alphad_fDS) / f_f;
}

DsZoneStudy studyDsZone(const Model& m, const GaitMotion<double>& mo, const DsLimits& l,
                        const std::vector<double>& grid) {
  DsZoneStudy s;
  s.alpha_iDS = alphaIDS(mo);
  s.alpha_fDS = alphaFDS(mo);
  s.cycle_alphad_iDS = mo.ds_alpha(0.0).first;
  s.cycle_alphad_fDS = mo.ds_alpha(mo.T_DS).first;
  const auto row = [&](double v) {
    const DsConvergenceZone z = dsConvergenceZone(m, mo, l, v);
    const double fastest = z.braking.end == "alpha_iDS" ? z.fastest(s.alpha_iDS) : kNaN;
    DsZoneRow r{v, fastest, z.slowest(s.alpha_iDS), z.braking.end, z.speeding_up.end,
                zeroDynamicsStepMap(mo, v), false, false};
    r.cycle_exists = r.fastest_iDS <= r.a && r.a <= r.slowest_iDS;  // NaN: false
    r.cycle_stable = r.fastest_iDS < r.a && r.a < r.slowest_iDS;
    return r;
  };
  s.cycle = row(s.cycle_alphad_fDS);
  for (double v : grid) s.rows.push_back(row(v));
  s.cycle_margin_samples = 101;
  s.cycle_braking_margin = s.cycle_speeding_up_margin = std::numeric_limits<double>::infinity();
  for (int k = 0; k < s.cycle_margin_samples; ++k) {
    const double alpha = s.alpha_fDS + (s.alpha_iDS - s.alpha_fDS) * k / (s.cycle_margin_samples - 1);
    const CyclicDsPoint c = cyclicDsAlpha(mo, alpha);
    const DsAccelerationBounds b = dsAccelerationBounds(m, mo, l, alpha, c.alphad);
    if (!b.defined) {  // H1 fails on the cycle itself
      s.cycle_braking_margin = s.cycle_speeding_up_margin = kNaN;
      break;
    }
    const double alphadd_c = c.slope * c.alphad;
    s.cycle_braking_margin = std::min(s.cycle_braking_margin, b.max - alphadd_c);
    s.cycle_speeding_up_margin = std::min(s.cycle_speeding_up_margin, alphadd_c - b.min);
  }
  const double a = s.cycle_alphad_iDS;
  s.cycle_in_zone = s.cycle.fastest_iDS <= a && a <= s.cycle.slowest_iDS;
  s.cycle_strictly_inside = s.cycle.fastest_iDS < a && a < s.cycle.slowest_iDS;
  s.from_rest = runTimeOptimalDs(m, mo, l, s.alpha_iDS, 0.0);
  s.existence_low = s.existence_high = kNaN;
  std::size_t c = 0;
  for (std::size_t i = 0; i < s.rows.size(); ++i)
    if (std::abs(s.rows[i].alphad_fDS - s.cycle_alphad_fDS) <
        std::abs(s.rows[c].alphad_fDS - s.cycle_alphad_fDS))
      c = i;
  if (s.rows.empty() || !s.rows[c].cycle_exists) return s;
  std::size_t lo = c, hi = c;
  while (lo > 0 && s.rows[lo - 1].cycle_exists) --lo;
  while (hi + 1 < s.rows.size() && s.rows[hi + 1].cycle_exists) ++hi;
  s.existence_low = std::min(s.rows[lo].alphad_fDS, s.rows[hi].alphad_fDS);
  s.existence_high = std::max(s.rows[lo].alphad_fDS, s.rows[hi].alphad_fDS);
  return s;
}

}  // namespace gaitopt
