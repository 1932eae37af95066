#include "gaitopt/opt/evaluation_cache.hpp"

#include <algorithm>
#include <cmath>

namespace gaitopt {

const GaitEvaluation<double>& GaitEvaluationCache::values(const GaitParameters& p) {
  if (holdsGradient(p)) return gradient_.value;
  if (!value_at_ || *value_at_ != p) {
    values_ = evaluator_.evaluate(p);
    value_at_ = p;
    ++value_count_;
  }
  return values_;
}

const GaitGradient& GaitEvaluationCache::gradient(const GaitParameters& p) {
  if (!gradient_at_ || *gradient_at_ != p) {
    gradient_ = mode_ == GradientMode::Exact
                    ? evaluator_.evaluateWithGradient(p, ds_piece_gradients_)
                    : finiteDifferenceGradient(p);
    gradient_at_ = p;
    ++gradient_count_;
  }
  return gradient_;
}

const BetweenNodesCheck& GaitEvaluationCache::betweenNodes(const GaitParameters& p) {
  if (!between_nodes_at_ || *between_nodes_at_ != p) {
    between_nodes_ = checkBetweenNodes(evaluator_, p);
    between_nodes_at_ = p;
  }
  return between_nodes_;
}

void GaitEvaluationCache::setDsPieceGradients(bool on) {
  if (on && !ds_piece_gradients_) gradient_at_.reset();  // the cached one lacks them
  ds_piece_gradients_ = on;
}

namespace {

// Column i of `d` (rows: the point's `values`): the central differences of the two sides'
// values, left at zero when a side has another number of them (another DS split).
void differenceColumn(Eigen::MatrixXd& d, int i, int n, const std::vector<double>& values,
                      const std::vector<double>& plus, const std::vector<double>& minus,
                      double h) {
  if (d.size() == 0) d.setZero(static_cast<int>(values.size()), n);
  if (plus.size() != values.size() || minus.size() != values.size()) return;
  for (int k = 0; k < d.rows(); ++k) d(k, i) = (plus[k] - minus[k]) / (2.0 * h);
}

// The same for one vector per DS piece.
void differencePieces(std::vector<Eigen::MatrixXd>& d, int i, int n,
                      const std::vector<std::vector<double>>& values,
                      const std::vector<std::vector<double>>& plus,
                      const std::vector<std::vector<double>>& minus, double h) {
  d.resize(values.size());
  const bool same = plus.size() == values.size() && minus.size() == values.size();
  for (std::size_t piece = 0; piece < d.size(); ++piece)
    differenceColumn(d[piece], i, n, values[piece], same ? plus[piece] : std::vector<double>(),
                     same ? minus[piece] : std::vector<double>(), h);
}

}  // namespace

// Step h_i = 1e-6 · max(1, |p_i|): near the optimum of the truncation/rounding trade-off for
// central differences of double-precision values.
GaitGradient GaitEvaluationCache::finiteDifferenceGradient(const GaitParameters& p) {
  GaitGradient r;
  r.value = evaluator_.evaluate(p);
  const int m = evaluator_.layout().size();
  const int n = static_cast<int>(p.size());
  r.dg.setZero(m, n);
  for (GaitParameters* g : {&r.dC_Gamma, &r.dC_E, &r.dW, &r.dC_frott, &r.dT_SS, &r.dT_DS, &r.dspeed})
    g->setZero(n);
  for (int i = 0; i < n; ++i) {
    const double h = 1e-6 * std::max(1.0, std::abs(p(i)));
    GaitParameters pp = p, pm = p;
    pp(i) += h;
    pm(i) -= h;
    const GaitEvaluation<double> ep = evaluator_.evaluate(pp), em = evaluator_.evaluate(pm);
    value_count_ += 2;
    const auto diff = [h](double a, double b) { return (a - b) / (2.0 * h); };
    for (int k = 0; k < m; ++k)
      if (ep.state[k] != ConstraintState::NotComputed && em.state[k] != ConstraintState::NotComputed)
        r.dg(k, i) = diff(ep.g[k], em.g[k]);
    r.dC_Gamma(i) = diff(ep.C_Gamma, em.C_Gamma);
    r.dC_E(i) = diff(ep.C_E, em.C_E);
    r.dW(i) = diff(ep.W, em.W);
    r.dC_frott(i) = diff(ep.C_frott, em.C_frott);
    r.dT_SS(i) = diff(ep.T_SS, em.T_SS);
    r.dT_DS(i) = diff(ep.T_DS, em.T_DS);
    r.dspeed(i) = diff(ep.speed, em.speed);
    // The joint speeds and the DS piece samples, when both sides split the DS as the point.
    const GaitEvaluation<double>& e = r.value;
    differenceColumn(r.dss_joint_speeds, i, n, e.ss_joint_speeds, ep.ss_joint_speeds,
                     em.ss_joint_speeds, h);
    differenceColumn(r.dds_joint_speeds, i, n, e.ds_joint_speeds, ep.ds_joint_speeds,
                     em.ds_joint_speeds, h);
    differencePieces(r.dds_piece_g, i, n, e.ds_piece_g, ep.ds_piece_g, em.ds_piece_g, h);
    differencePieces(r.dds_piece_speeds, i, n, e.ds_piece_speeds, ep.ds_piece_speeds,
                     em.ds_piece_speeds, h);
  }
  return r;
}

}  // namespace gaitopt
