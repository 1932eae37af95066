#include "gaitopt/gait_evaluator.hpp"

#include <unsupported/Eigen/AutoDiff>

#include "gaitopt/gait_evaluator_impl.hpp"

namespace gaitopt {
namespace {

using GaitAD = Eigen::AutoDiffScalar<Eigen::Matrix<double, kNumGaitParameters, 1>>;

Model gaitModel(const RobotParams& robot, const GaitOptions& options, const ModelOptions& mo) {
  Model m = buildModel(robot, mo);
  if (!options.dry_friction) m.coulomb.setZero();  // viscous-only results of §3.6
  return m;
}

GaitParameters derivativeOf(const GaitAD& x) { return x.derivatives(); }

}  // namespace

GaitEvaluator::GaitEvaluator(const RobotParams& robot, const GaitOptions& options,
                             const ModelOptions& model_options)
    : model_(gaitModel(robot, options, model_options)),
      options_(options),
      layout_(options),
      grids_(options) {}

GaitEvaluation<double> GaitEvaluator::evaluate(const GaitParameters& p) const {
  GaitEvaluation<double> out;
  detail::evaluateGaitImpl(model_, options_, layout_, grids_, p, out);
  return out;
}

GaitGradient GaitEvaluator::evaluateWithGradient(const GaitParameters& p) const {
  GaitGradient r;
  // The double pass gives the values and the DS pieces the AD pass integrates over.
  r.value = evaluate(p);
  GaitVector<GaitAD> pad;
  for (int i = 0; i < kNumGaitParameters; ++i) pad(i) = GaitAD(p(i), kNumGaitParameters, i);
  GaitEvaluation<GaitAD> ad;
  detail::evaluateGaitImpl(model_, options_, layout_, grids_, pad, ad, &r.value.ds_pieces);
  r.dg.resize(layout_.size(), kNumGaitParameters);
  for (int k = 0; k < layout_.size(); ++k) {
    const auto& der = ad.g[k].derivatives();
    if (der.size() == kNumGaitParameters)
      r.dg.row(k) = der.transpose();
    else
      r.dg.row(k).setZero();  // entry never touched an AD operation (a constant)
  }
  const auto grad = [](const GaitAD& x) {
    return x.derivatives().size() == kNumGaitParameters ? derivativeOf(x)
                                                        : GaitParameters(GaitParameters::Zero());
  };
  r.dC_Gamma = grad(ad.C_Gamma);
  r.dC_E = grad(ad.C_E);
  r.dW = grad(ad.W);
  r.dC_frott = grad(ad.C_frott);
  r.dT_SS = grad(ad.T_SS);
  r.dT_DS = grad(ad.T_DS);
  r.dspeed = grad(ad.speed);
  return r;
}

}  // namespace gaitopt
