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
    // The DS piece samples, when both sides split the DS as the point does.
    r.dds_piece_g.resize(r.value.ds_piece_g.size());
    for (std::size_t piece = 0; piece < r.dds_piece_g.size(); ++piece) {
      Eigen::MatrixXd& d = r.dds_piece_g[piece];
      if (d.size() == 0) d.setZero(static_cast<int>(r.value.ds_piece_g[piece].size()), n);
      if (ep.ds_piece_g.size() != r.dds_piece_g.size() || em.ds_piece_g.size() != r.dds_piece_g.size())
        continue;
      for (int k = 0; k < d.rows(); ++k) d(k, i) = diff(ep.ds_piece_g[piece][k], em.ds_piece_g[piece][k]);
    }
  }
  return r;
}

}  // namespace gaitopt
