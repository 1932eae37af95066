#include "gaitopt/gait/evaluator.hpp"

#include <stdexcept>
#include <unsupported/Eigen/AutoDiff>

#include "gaitopt/gait/evaluator_impl.hpp"

namespace gaitopt {
namespace {

// Fixed-size derivative vectors: Eigen's AutoDiffScalar gives a dynamic-size constant an empty
// derivative, which its compound assignments do not reconcile. The thesis' 17 parameters get
// exactly 17 directions; richer parameterisations the next bucket (unused directions stay 0).
template <int N> using GaitAD = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;

Model gaitModel(const RobotParams& robot, const GaitOptions& options, const ModelOptions& mo) {
  Model m = buildModel(robot, mo);
  // The same friction (1.21) as the exported feedforward (export/controller_export.cpp): the
  // robot's Coulomb and viscous friction with the smooth sign of width friction_smoothing.
  // Without dry friction, viscous only (the §3.6 results).
  if (!options.dry_friction) m.coulomb.setZero();
  return m;
}

template <class AD> GaitParameters gradientOf(const AD& x, int n) {
  return x.derivatives().head(n);
}

// The gradients of a vector of AD values, one row each.
template <class AD> Eigen::MatrixXd gradientsOf(const std::vector<AD>& x, int n) {
  Eigen::MatrixXd d(static_cast<int>(x.size()), n);
  for (int k = 0; k < d.rows(); ++k) d.row(k) = gradientOf(x[k], n).transpose();
  return d;
}

}  // namespace

GaitEvaluator::GaitEvaluator(const RobotParams& robot, const GaitOptions& options,
                             const ModelOptions& model_options)
    : model_(gaitModel(robot, options, model_options)),
      options_(options),
      layout_(options),
      grids_(options) {
  if (options.parameterisation.ss_points < 1 || options.parameterisation.ss_points % 2 == 0 ||
      options.parameterisation.ds_points < 0 ||
      (!options.parameterisation.hasDoubleSupport() && options.parameterisation.ds_points > 0) ||
      options.parameterisation.size() > kMaxGaitParameters)
    throw std::invalid_argument("unsupported parameterisation " +
                                options.parameterisation.label());
  if (options.touchdown_speed_min > 0.0 && !options.parameterisation.landsWithImpact())
    throw std::invalid_argument("touchdown_speed_min needs a landing with impact (the "
                                "zero-velocity landing meets the ground at rest)");
}

GaitEvaluator GaitEvaluator::withCriteriaRefinement(int refinement) const {
  GaitEvaluator r = *this;
  r.options_.criteria_refinement = refinement;
  r.grids_ = GaitGrids(r.options_);
  return r;
}

void GaitEvaluator::checkSize(const GaitParameters& p) const {
  if (p.size() != numParameters())
    throw std::invalid_argument("gait parameters: expected " + std::to_string(numParameters()) +
                                " values for " + options_.parameterisation.label() + ", got " +
                                std::to_string(p.size()));
}

GaitEvaluation<double> GaitEvaluator::evaluate(const GaitParameters& p) const {
  checkSize(p);
  GaitEvaluation<double> out;
  detail::evaluateGaitImpl(model_, options_, layout_, grids_, p, out);
  return out;
}

template <class AD>
GaitGradient GaitEvaluator::gradientWith(const GaitParameters& p, bool ds_piece_gradients) const {
  const int n = numParameters();
  GaitGradient r;
  // The double pass gives the values and the DS pieces the AD pass integrates over.
  r.value = evaluate(p);
  constexpr int directions = AD::DerType::RowsAtCompileTime;
  GaitVector<AD> pad(n);
  for (int i = 0; i < n; ++i) pad(i) = AD(p(i), directions, i);
  GaitEvaluation<AD> ad;
  detail::evaluateGaitImpl(model_, options_, layout_, grids_, pad, ad, &r.value.ds_pieces,
                           ds_piece_gradients);
  r.dg = gradientsOf(ad.g, n);
  r.dC_Gamma = gradientOf(ad.C_Gamma, n);
  r.dC_E = gradientOf(ad.C_E, n);
  r.dW = gradientOf(ad.W, n);
  r.dC_frott = gradientOf(ad.C_frott, n);
  r.dT_SS = gradientOf(ad.T_SS, n);
  r.dT_DS = gradientOf(ad.T_DS, n);
  r.dspeed = gradientOf(ad.speed, n);
  r.dcriteria_kinks = gradientsOf(ad.criteria_kinks, n);
  r.dtorque_residuals = gradientsOf(ad.torque_residuals, n);
  r.dss_joint_speeds = gradientsOf(ad.ss_joint_speeds, n);
  r.dds_joint_speeds = gradientsOf(ad.ds_joint_speeds, n);
  for (const auto& piece : ad.ds_piece_g) r.dds_piece_g.push_back(gradientsOf(piece, n));
  for (const auto& piece : ad.ds_piece_speeds)
    r.dds_piece_speeds.push_back(gradientsOf(piece, n));
  return r;
}

GaitGradient GaitEvaluator::evaluateWithGradient(const GaitParameters& p,
                                                 bool ds_piece_gradients) const {
  checkSize(p);
  const int n = numParameters();
  if (n == kNumGaitParameters)
    return gradientWith<GaitAD<kNumGaitParameters>>(p, ds_piece_gradients);
  if (n <= 32) return gradientWith<GaitAD<32>>(p, ds_piece_gradients);
  return gradientWith<GaitAD<kMaxGaitParameters>>(p, ds_piece_gradients);
}

}  // namespace gaitopt
