// The last-resort `inertial` stage of the diagnosis.
#include "gaitopt/ident/inertial_stage.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace gaitopt::diagnosis {

namespace {

struct InertialStage {
  InertialResult result;
  RobotParams robot;
  Eigen::MatrixXd Y;  // weighted regressor, fit entries
  std::array<double, kNumChannels> sigma{};
  Evaluation r;       // residuals of the fitted model
};

// The last-resort `inertial` candidate on top of the accepted model `base` (robot `rb`):
// regressor columns by finite differences (exact: the residuals are affine in the
// parameters), physically consistent weighted LS, reweighted once with the noise levels the
// fit leaves, then the tests of the named candidates with r = rank degrees of freedom.
InertialStage fitInertial(const Context& ctx, const RobotParams& rb, const Fit& base,
                          std::array<double, kNumChannels> sigma, const DiagnoseOptions& o) {
  const std::vector<Entry>& fe = ctx.fit.entries;
  const std::vector<Entry>& he = ctx.held.entries;
  std::vector<Evaluation> cols(kNumInertialParameters);
  parallelFor(kNumInertialParameters, [&](int k) {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(kNumInertialParameters);
    d(k) = inertialScale(k);
    const Evaluation r = ctx.evaluate(withInertialChange(rb, d));
    cols[k] = {(r.fit - base.r.fit) / d(k), (r.held - base.r.held) / d(k)};
  });
  Eigen::MatrixXd Y(fe.size(), kNumInertialParameters);
  ConsistentFit cf;
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      Eigen::VectorXd r = base.r.fit;
      for (int k = 0; k < kNumInertialParameters; ++k) r += cols[k].fit * cf.delta(k);
      sigma = channelSigma(ctx.fit, fitMatrix(ctx.fit.prepared.data.size(), fe, r));
    }
    double column_norm2 = 0.0;  // mean squared norm of the scaled columns
    for (int k = 0; k < kNumInertialParameters; ++k) {
      Y.col(k) = weightedVector(fe, cols[k].fit, sigma);
      column_norm2 += (Y.col(k) * inertialScale(k)).squaredNorm() / kNumInertialParameters;
    }
    // λ: 1e-6 of the data's weight, enough to pin the directions the data do not excite.
    cf = consistentLeastSquares(Y, weightedVector(fe, base.r.fit, sigma), rb, 1e-6 * column_norm2);
  }
  InertialStage st;
  InertialResult& ir = st.result;
  ir.tried = true;
  ir.active = cf.active;
  st.robot = withInertialChange(rb, cf.delta);
  st.Y = Y;
  st.sigma = sigma;
  st.r = ctx.evaluate(st.robot);
  const Evaluation& ev = st.r;
  const Eigen::VectorXd rb_w = weightedVector(fe, base.r.fit, sigma);
  const Eigen::VectorXd r_w = weightedVector(fe, ev.fit, sigma);
  ir.base = baseParameters(Y);
  const double n = static_cast<double>(fe.size());
  const double phi = signalInflation(fe, rb_w, r_w);
  const double s2 = r_w.squaredNorm() / std::max(1.0, n - base.effects.size() - ir.base.rank);
  ir.p_value = chi2Survival((rb_w.squaredNorm() - r_w.squaredNorm()) / (phi * s2), ir.base.rank);
  ir.nominal = inertialParameters(rb);
  ir.fitted = inertialParameters(st.robot);
  ir.base_nominal = ir.base.values(ir.nominal);
  ir.base_fitted = ir.base.values(ir.fitted);
  Eigen::MatrixXd Yb(fe.size(), ir.base.rank);
  for (int i = 0; i < ir.base.rank; ++i) Yb.col(i) = Y.col(ir.base.independent[i]);
  const Eigen::MatrixXd YtY = Yb.transpose() * Yb;
  ir.base_stderr = (phi * s2 * YtY.ldlt().solve(Eigen::MatrixXd::Identity(ir.base.rank, ir.base.rank)))
                       .diagonal().cwiseMax(0.0).cwiseSqrt();
  const Eigen::VectorXd hb = weightedVector(he, base.r.held, sigma);
  const Eigen::VectorXd h = weightedVector(he, ev.held, sigma);
  ir.holdout_rms_before = std::sqrt(hb.squaredNorm() / std::max<Eigen::Index>(1, hb.size()));
  ir.holdout_rms_after = std::sqrt(h.squaredNorm() / std::max<Eigen::Index>(1, h.size()));
  ir.accepted = ir.p_value < o.significance &&
                ir.holdout_rms_after < (1.0 - o.min_inertial_gain / 100.0) * ir.holdout_rms_before &&
                bestChannelGain(he, base.r.held, ev.held) >= o.min_channel_gain;
  return st;
}

// Backward step once `inertial` is in the model: the accepted named effects (candidate
// indices `accepted`, fitted values in `named`) that are no longer significant given the
// others and the inertial parameters (linearised likelihood-ratio test at the final model).
std::vector<int> supersededByInertial(const Context& ctx, const Linearisation& lin,
                                      const std::vector<int>& accepted,
                                      const std::vector<Effect>& named, const InertialStage& st,
                                      double significance) {
  const std::vector<Entry>& fe = ctx.fit.entries;
  const Eigen::VectorXd rf = weightedVector(fe, st.r.fit, st.sigma);
  const double n = static_cast<double>(fe.size());
  const double s2 = rf.squaredNorm() / std::max(1.0, n - accepted.size() - st.result.base.rank);
  const double phi = inflation(fe, rf);
  std::vector<int> dropped;
  for (std::size_t i = 0; i < accepted.size(); ++i) {
    Eigen::MatrixXd A(fe.size(), st.Y.cols() + accepted.size() - 1);
    A.leftCols(st.Y.cols()) = st.Y;
    Eigen::Index col = st.Y.cols();
    for (std::size_t j = 0; j < accepted.size(); ++j)
      if (j != i) A.col(col++) = weightedVector(fe, lin.columns[accepted[j]].fit, st.sigma);
    const Effect& e = named[i];
    const double deviation = effectInfo(e.kind).factor ? e.value - 1.0 : e.value;
    const Eigen::VectorXd b = rf - weightedVector(fe, lin.columns[accepted[i]].fit, st.sigma) * deviation;
    const Eigen::VectorXd x = A.colPivHouseholderQr().solve(-b);
    const double drss = (b + A * x).squaredNorm() - rf.squaredNorm();
    if (chi2Survival(drss / (phi * s2)) >= significance) dropped.push_back(static_cast<int>(i));
  }
  return dropped;
}

}  // namespace

void addInertialStage(const Context& ctx, const Linearisation& lin, const Selection& sel,
                      const DiagnoseOptions& o, Diagnosis& dg) {
  const auto stage = [&](const Fit& b) {
    const ResidualMatrix r = fitMatrix(ctx.fit.prepared.data.size(), ctx.fit.entries, b.r.fit);
    return fitInertial(ctx, withEffects(ctx.fit.nominal, b.effects), b, channelSigma(ctx.fit, r),
                       o);
  };
  InertialStage st = stage(sel.model);
  const std::vector<int> dropped =
      st.result.accepted ? supersededByInertial(ctx, lin, sel.accepted, sel.model.effects, st, o.significance)
                         : std::vector<int>{};
  if (!dropped.empty()) {  // refit the named effects that remain, then the inertial ones
    std::vector<int> keep;
    std::vector<Cause> causes;
    for (std::size_t i = 0; i < sel.accepted.size(); ++i)
      if (std::find(dropped.begin(), dropped.end(), static_cast<int>(i)) == dropped.end()) {
        keep.push_back(sel.accepted[i]);
        causes.push_back(dg.causes[i]);
      }
    const Fit reduced = keep.empty() ? Fit{{}, lin.r0, {}}
                                     : gaussNewton(ctx, chordFit(ctx, lin, keep, sel.sigma, kIterations), sel.sigma, 3);
    InertialStage st2 = stage(reduced);
    if (st2.result.accepted) {
      for (std::size_t i = 0; i < causes.size(); ++i) causes[i].effect.value = reduced.effects[i].value;
      dg.causes = causes;
      st = std::move(st2);
    }
  }
  dg.inertial = st.result;
  if (st.result.accepted) {
    dg.causes.push_back({{EffectKind::Inertial, kNoJoint, kNaN}, kNaN, st.result.p_value, {}, {}});
    dg.extended_robot = st.robot;
  }
}

}  // namespace gaitopt::diagnosis
