#include "gaitopt/gait/richer_parameterisation.hpp"

#include <stdexcept>


namespace gaitopt {
namespace {

// θ3 from (3.17): θ3 = α + δ1 − δ2 + π/2.
double trunkAngle(double alpha, double delta1, double delta2) {
  return alpha + delta1 - delta2 + 0.5 * M_PI;
}

}  // namespace

GaitParameters toRicherParameterisation(const GaitEvaluator& coarse, const GaitParameters& p,
                                const Parameterisation& fine) {
  const Parameterisation& from = coarse.options().parameterisation;
  if (fine.ss_points < from.ss_points || fine.ds_points < from.ds_points ||
      (from.landsWithImpact() && !fine.landsWithImpact()))
    throw std::invalid_argument("cannot refine " + from.label() + " into " + fine.label());
  const GaitEvaluation<double> e = coarse.evaluate(p);
  if (e.failed_level == 0 || e.failed_level == 1)
    throw std::invalid_argument("cannot refine a step whose level " +
                                std::to_string(e.failed_level) + " fails");
  const GaitMotion<double>& mo = e.motion;
  GaitParameters out = extendPerParameter(p.head(kNumGaitParameters), fine, {0.0, 0.0}, {0.0, 0.0});
  for (int k = 0; k < fine.ss_points; ++k) {
    Vec5 q;
    q(0) = mo.alpha_iSS + fine.ssFraction(k) * (mo.alpha_fSS - mo.alpha_iSS);
    for (int j = 0; j < 4; ++j) q(j + 1) = mo.ss_path[j](q(0)).value;
    if (fine.isFootPoint(k)) {
      out.segment(kDelta1Int, 4) = p.segment(kDelta1Int, 4);  // the thesis' α_int point
      continue;
    }
    out.segment(fine.ssPointIndex(k), 4) << q(1), trunkAngle(q(0), q(1), q(2)), q(3), q(4);
  }
  // A landing with impact keeps the SS-end slopes δ3*, δ4* of the path (a zero-velocity
  // landing's are those of (3.20)).
  if (fine.landsWithImpact())
    for (int j = 0; j < 2; ++j) out(fine.impactSlopeIndex() + j) = mo.ss_path[j + 2](mo.alpha_fSS).first;
  for (int k = 0; k < fine.ds_points; ++k) {
    const double alpha = p(kAlphaIDS) + fine.dsFraction(k) * (p(kAlphaFDS) - p(kAlphaIDS));
    const double d1 = mo.ds_delta1(alpha).value, d2 = mo.ds_delta2(alpha).value;
    out.segment(fine.dsPointIndex(k), 2) << d1, trunkAngle(alpha, d1, d2);
  }
  return out;
}

}  // namespace gaitopt
