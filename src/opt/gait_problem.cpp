#include "gaitopt/opt/gait_problem.hpp"

#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include "gaitopt/gait/coulomb_split.hpp"
#include "gaitopt/gait/ds_interval_maxima.hpp"
#include "gaitopt/gait/feasibility.hpp"
#include "gaitopt/math/chebyshev_maxima.hpp"
#include "gaitopt/math/degree_cache.hpp"

namespace gaitopt {
namespace {

constexpr double kInf = 1e20;

GaitParameters toParameters(const VectorX& x) { return GaitParameters(x); }

bool motionAvailable(const GaitEvaluation<double>& e) { return e.motion_computed; }

// Which evaluation a result comes from: the point, and whether the cache answered with its
// gradient pass's values (GaitEvaluationCache::values). The values are a deterministic function
// of both, so what was computed under one key is the same numbers when asked again.
struct EvaluationKey {
  GaitParameters x;
  bool gradient = false;
  bool operator==(const EvaluationKey& o) const {
    return gradient == o.gradient && x.size() == o.x.size() && x == o.x;
  }
};

class CriterionCost : public CostTerm {
 public:
  CriterionCost(GaitEvaluationCache& cache, Criterion c, double scale)
      : cache_(cache), criterion_(c), scale_(scale) {}
  std::string name() const override { return criterionName(criterion_); }
  bool value(const VectorX& x, double& f) override {
    const GaitEvaluation<double>& e = cache_.values(toParameters(x));
    if (!motionAvailable(e)) return false;
    f = criterionValue(e, criterion_) / scale_;
    return true;
  }
  bool gradient(const VectorX& x, Eigen::Ref<VectorX> grad) override {
    const GaitGradient& g = cache_.gradient(toParameters(x));
    if (!motionAvailable(g.value)) return false;
    grad = criterionGradient(g, criterion_) / scale_;
    return true;
  }
  // C_Γ = Σ r_i² (GaitEvaluation::torque_residuals): its Gauss–Newton Hessian 2 JᵀJ from the
  // residuals' Jacobian, which the gradient pass computes anyway. W and C_E integrate kinked
  // integrands (|Γ*_j ω_j|, max(0, P)), no sum of squares: none.
  bool hasHessian() const override { return criterion_ == Criterion::Torque; }
  bool hessian(const VectorX& x, Eigen::Ref<MatrixX> hess) override {
    const GaitGradient& g = cache_.gradient(toParameters(x));
    if (!motionAvailable(g.value) || criterion_ != Criterion::Torque) return false;
    hess.noalias() = (2.0 / scale_) * g.dtorque_residuals.transpose() * g.dtorque_residuals;
    return true;
  }

 private:
  GaitEvaluationCache& cache_;
  Criterion criterion_;
  double scale_;
};

class DistanceCost : public CostTerm {
 public:
  DistanceCost(const GaitParameters& ref, const Parameterisation& par)
      : ref_(ref), w_(parameterScales(par).cwiseInverse().cwiseAbs2()) {}
  std::string name() const override { return "distance"; }
  bool value(const VectorX& x, double& f) override {
    f = (x - ref_).cwiseAbs2().dot(w_);  // (3.78) in the scaled norm
    return true;
  }
  bool gradient(const VectorX& x, Eigen::Ref<VectorX> grad) override {
    grad = 2.0 * w_.cwiseProduct(x - ref_);
    return true;
  }
  bool hasHessian() const override { return true; }
  bool hessian(const VectorX&, Eigen::Ref<MatrixX> hess) override {
    hess = (2.0 * w_).asDiagonal();
    return true;
  }

 private:
  GaitParameters ref_, w_;
};

// Where a phase-wise entry's row is taken between the nodes: the entry at node j stands for
// the interval [s_{j+1}, s_j] (the last node for itself), so that the rows hold the
// constraint on the whole phase with as many rows as nodes. The clearance has no entry at the
// phase ends (its value is 0 there): its end intervals are not rows.
struct BetweenNodeRow {
  int group = -1;             // −1: a row at its own entry
  int sub = 0, interval = 0;  // entry within the point, interval of the phase's grid
};

// The DS level-5 groups, whose values kink at the force split's switch times: their rows are
// maxima over the DS pieces (gait/ds_interval_maxima.hpp); the other phase-wise groups are
// smooth and use the interpolant of their node values.
bool piecewise(int group) { return group >= kTorqueDS && group <= kDsMonotone; }

class BetweenNodeRows {
 public:
  BetweenNodeRows(const GaitEvaluator& ev, const std::vector<int>& entries, BetweenNodes which)
      : ev_(ev), ss_(ev.ssGrid()), ds_(ev.dsGrid()), ds_pieces_(ev) {
    const ConstraintLayout& layout = ev.layout();
    for (int k : entries) {
      BetweenNodeRow r;
      for (int id = 0; id < kNumConstraintGroups; ++id) {
        const ConstraintGroup& g = layout[id];
        const bool held = g.phase == ConstraintPhase::SingleSupport ||
                          (g.phase == ConstraintPhase::DoubleSupport && which == BetweenNodes::Both);
        if (!held || k < g.offset || k >= g.offset + g.count) continue;
        const int node = (k - g.offset) / g.per_point + g.first_point;
        const int last = grid(g).degree() - (id == kClearance ? 1 : 0);
        if (node < last) r = {id, (k - g.offset) % g.per_point, node};
      }
      uses_pieces_ = uses_pieces_ || piecewise(r.group);
      if (r.group >= 0 && !piecewise(r.group) && !sequences_.count(key(r))) {
        sequences_[key(r)] = sequenceOf(r);
        const CoulombSplit split = coulombSplit(ev.model(), r.group, r.sub);
        if (split.coulomb != 0.0) {
          splits_[key(r)] = split;
          fine_ = sharedByDegree<MatrixX>(ev.ssGrid().degree(), fineInterpolation);
        }
      }
      rows_.push_back(r);
    }
  }
  // The interval maxima of every row's sequence at an evaluation (false: one is not computed);
  // kept while the evaluation's key stays the same.
  bool update(const GaitEvaluation<double>& e, const EvaluationKey& at) {
    if (at_ && *at_ == at) return true;
    at_.reset();
    maxima_.clear();
    sampled_.clear();
    if (uses_pieces_ && !ds_pieces_.update(e)) return false;
    for (const BetweenNodeRow& r : rows_) {
      if (r.group < 0 || piecewise(r.group) || maxima_.count(key(r)) || sampled_.count(key(r)))
        continue;
      Eigen::VectorXd values = Eigen::VectorXd::Zero(grid(ev_.layout()[r.group]).size());
      for (const auto& [node, k] : sequences_.at(key(r))) {
        if (e.state[k] == ConstraintState::NotComputed) return false;
        values[node] = e.g[k];
      }
      if (splits_.count(key(r))) {
        sampled_[key(r)] = splitMaxima(splits_.at(key(r)), r, e, values);
        continue;
      }
      const bool ss = ev_.layout()[r.group].phase == ConstraintPhase::SingleSupport;
      maxima_[key(r)] = (ss ? ss_ : ds_)(values);
    }
    at_ = at;
    return true;
  }
  int size() const { return static_cast<int>(rows_.size()); }
  bool usesPieces() const { return uses_pieces_; }
  bool between(int row) const { return rows_[row].group >= 0; }
  double value(int row) const {
    const BetweenNodeRow& r = rows_[row];
    if (piecewise(r.group)) return ds_pieces_.maximum(r.group, r.sub, r.interval).value;
    return splits_.count(key(r)) ? sampled(row).value : maximum(row).value;
  }
  // Envelope theorem: Σ_m l_m(s*) ∇g_m into `out`; dg_t = gr.dg transposed, so that each ∇g_m
  // is a contiguous column (a Jacobian sums ~30 of them for each of ~1000 rows).
  void gradient(int row, const GaitGradient& gr, const MatrixX& dg_t,
                Eigen::Ref<VectorX> out) {
    const BetweenNodeRow& r = rows_[row];
    if (piecewise(r.group)) {
      out = ds_pieces_.gradient(r.group, r.sub, r.interval, gr);
      return;
    }
    const auto split = splits_.find(key(r));
    if (split == splits_.end())
      lagrangeBasis(grid(ev_.layout()[r.group]), maximum(row).s, basis_);
    else
      basis_ = fine_->row(sampled(row).sample).transpose();
    const Sequence& q = sequences_.at(key(r));
    if (out.size() == kNumGaitParameters)
      sumColumns<Eigen::Matrix<double, kNumGaitParameters, 1>>(q, dg_t, out);
    else
      sumColumns<VectorX>(q, dg_t, out);
    if (split != splits_.end()) addCoulombGradient(split->second, row, gr, out);
  }

 private:
  const ChebyshevGrid& grid(const ConstraintGroup& g) const {
    return g.phase == ConstraintPhase::SingleSupport ? ev_.ssGrid() : ev_.dsGrid();
  }
  using Sequence = std::vector<std::pair<int, int>>;  // (node, layout entry)
  static int key(const BetweenNodeRow& r) { return r.group * 64 + r.sub; }
  // Σ_m l_m ∇g_m in an `Acc`: of fixed size for the thesis' 17 parameters, which keeps the sum
  // in registers over the ~30 columns (the same additions, in the same order).
  template <class Acc>
  void sumColumns(const Sequence& q, const MatrixX& dg_t, Eigen::Ref<VectorX> out) const {
    Acc sum = Acc::Zero(out.size());
    for (const auto& [node, k] : q) sum += basis_[node] * dg_t.col(k);
    out = sum;
  }
  const InterpolantMaximum& maximum(int row) const {
    return maxima_.at(key(rows_[row]))[rows_[row].interval];
  }
  // A split row's value on an interval: its largest sample, the verdict's finer grid's node.
  struct SampledMaximum {
    int sample = 0;  // node of the finer grid
    double value = 0.0;
    double w = 0.0;  // σω there
  };
  const SampledMaximum& sampled(int row) const {
    return sampled_.at(key(rows_[row]))[rows_[row].interval];
  }
  // Interpolation from the nodes of a grid of degree n onto the verdict's finer grid, whose
  // node kBetweenNodesRefinement·k is node k (math/degree_cache.hpp shares it per degree).
  static MatrixX fineInterpolation(int n) {
    const ChebyshevGrid grid(n), fine(n * kBetweenNodesRefinement);
    MatrixX p(fine.size(), grid.size());
    Eigen::VectorXd l;
    for (int i = 0; i < fine.size(); ++i) {
      lagrangeBasis(grid, fine.nodes()[i], l);
      p.row(i) = l.transpose();
    }
    return p;
  }
  double jointSpeed(const GaitEvaluation<double>& e, const CoulombSplit& c, int node) const {
    return e.ss_joint_speeds[4 * node + c.joint];
  }
  // gait/coulomb_split.hpp: the row's node values `g` become its smooth part h; h and σω are
  // interpolated onto the finer grid, where each interval's largest row is kept.
  std::vector<SampledMaximum> splitMaxima(const CoulombSplit& c, const BetweenNodeRow& r,
                                          const GaitEvaluation<double>& e, Eigen::VectorXd& g) {
    Eigen::VectorXd speed = Eigen::VectorXd::Zero(g.size());
    for (const auto& [node, k] : sequences_.at(key(r))) {
      g[node] -= c.term(jointSpeed(e, c, node));
      speed[node] = c.sigma * jointSpeed(e, c, node);
    }
    const Eigen::VectorXd h = *fine_ * g, w = *fine_ * speed;
    Eigen::VectorXd row(h.size());  // one tanh per point: a node ends two intervals
    for (int i = 0; i < row.size(); ++i) row[i] = c.row(h[i], w[i]);
    std::vector<SampledMaximum> out(g.size() - 1);
    for (int k = 0; k + 1 < g.size(); ++k)
      for (int i = kBetweenNodesRefinement * k; i <= kBetweenNodesRefinement * (k + 1); ++i)
        if (i == kBetweenNodesRefinement * k || row[i] > out[k].value) out[k] = {i, row[i], w[i]};
    return out;
  }
  // The row's gradient beyond Σ_m P_m ∇g_m (in `out`, P the sample's interpolation row):
  // Σ_m c_m ∇ω_m with c_m = P_m (σ row'(w) − term'(ω_m)), the sample held fixed.
  void addCoulombGradient(const CoulombSplit& c, int row, const GaitGradient& gr,
                          Eigen::Ref<VectorX> out) {
    const double top = c.rowSlope(sampled(row).w);
    for (const auto& [node, k] : sequences_.at(key(rows_[row]))) {
      const double coefficient =
          basis_[node] * c.sigma * (top - c.rowSlope(jointSpeed(gr.value, c, node)));
      out += coefficient * gr.dss_joint_speeds.row(4 * node + c.joint).transpose();
    }
  }
  // (node, layout entry) of every entry of a row's sequence.
  Sequence sequenceOf(const BetweenNodeRow& r) const {
    const ConstraintGroup& g = ev_.layout()[r.group];
    Sequence out;
    for (int i = 0; i < g.count / g.per_point; ++i)
      out.emplace_back(i + g.first_point, g.offset + i * g.per_point + r.sub);
    return out;
  }

  const GaitEvaluator& ev_;
  IntervalMaxima ss_, ds_;
  DsIntervalMaxima ds_pieces_;
  bool uses_pieces_ = false;
  std::vector<BetweenNodeRow> rows_;
  std::map<int, std::vector<InterpolantMaximum>> maxima_;
  std::map<int, CoulombSplit> splits_;  // by key, the rows with Coulomb friction
  std::map<int, std::vector<SampledMaximum>> sampled_;  // by key, theirs
  std::shared_ptr<const MatrixX> fine_;  // fineInterpolation, when a row is split
  std::map<int, Sequence> sequences_;  // by key, the smooth groups'
  std::optional<EvaluationKey> at_;  // of maxima_
  Eigen::VectorXd basis_;            // the Lagrange basis of the row at hand
};

class HierarchyConstraints : public ConstraintSet {
 public:
  HierarchyConstraints(GaitEvaluationCache& cache, const std::vector<int>& entries,
                       double interior, double level5_interior, BetweenNodes between_nodes)
      : cache_(cache), rows_(entries), interior_(interior), level5_interior_(level5_interior),
        between_(cache.evaluator(),
                 between_nodes != BetweenNodes::None ? entries : std::vector<int>(),
                 between_nodes) {
    const ConstraintLayout& layout = cache.evaluator().layout();
    for (int e : rows_) scales_.push_back(constraintScale(layout, cache.evaluator().model(), e));
    cache.setDsPieceGradients(between_.usesPieces());
  }
  std::string name() const override { return "hierarchy"; }
  int size() const override { return static_cast<int>(rows_.size()); }
  void bounds(Eigen::Ref<VectorX> lower, Eigen::Ref<VectorX> upper) const override {
    // The evaluator fails levels 0–4 at g > 0, so the solver aims strictly inside them (its own
    // feasibility tolerance would otherwise leave g ≈ +1e-7·scale); level 5 only when asked.
    lower.setConstant(-kInf);
    const ConstraintLayout& layout = cache_.evaluator().layout();
    for (int i = 0; i < size(); ++i)
      upper(i) = layout.levelOf(rows_[i]) < 5 ? -interior_ : -level5_interior_;
  }
  bool values(const VectorX& x, Eigen::Ref<VectorX> g) override {
    const EvaluationKey at{toParameters(x), cache_.holdsGradient(toParameters(x))};
    if (!(values_.at && *values_.at == at)) {
      values_.at = at;
      values_.ok = computeValues(cache_.values(at.x), at);
    }
    g = values_.rows;
    return values_.ok;
  }
  bool jacobian(const VectorX& x, Eigen::Ref<MatrixX> jac) override {
    const EvaluationKey at{toParameters(x), true};
    if (!(jacobian_.at && *jacobian_.at == at)) {
      jacobian_.at = at;
      jacobian_.ok = computeJacobian(cache_.gradient(at.x), at);
    }
    jac = jacobian_.rows.transpose();
    return jacobian_.ok;
  }
  int layoutEntry(int row) const { return rows_[row]; }

 private:
  bool between(int row) const { return between_.size() > 0 && between_.between(row); }

  bool computeValues(const GaitEvaluation<double>& e, const EvaluationKey& at) {
    values_.rows.resize(size());
    if (!between_.update(e, at)) return false;
    for (int i = 0; i < size(); ++i) {
      if (e.state[rows_[i]] == ConstraintState::NotComputed) return false;
      values_.rows(i) = (between(i) ? between_.value(i) : e.g[rows_[i]]) / scales_[i];
    }
    return true;
  }
  // Assembled transposed (a row's gradient is a contiguous column).
  bool computeJacobian(const GaitGradient& gr, const EvaluationKey& at) {
    MatrixX& jac_t = jacobian_.rows;
    jac_t.resize(gr.dg.cols(), size());
    if (!between_.update(gr.value, at)) return false;
    dg_t_ = gr.dg.transpose();
    for (int i = 0; i < size(); ++i) {
      if (gr.value.state[rows_[i]] == ConstraintState::NotComputed) return false;
      if (between(i))
        between_.gradient(i, gr, dg_t_, jac_t.col(i));
      else
        jac_t.col(i) = dg_t_.col(rows_[i]);
      jac_t.col(i) /= scales_[i];
    }
    return true;
  }

  // The rows at the last point asked, by its evaluation's key: NLopt asks for every row from
  // each of its constraint callbacks (equalities, inequalities) at the same point, and an
  // evaluation is a deterministic function of its key, so the kept rows are the same numbers.
  template <class Rows>
  struct Kept {
    std::optional<EvaluationKey> at;
    bool ok = false;
    Rows rows;
  };

  GaitEvaluationCache& cache_;
  std::vector<int> rows_;
  std::vector<double> scales_;
  double interior_, level5_interior_;
  BetweenNodeRows between_;
  Kept<VectorX> values_;
  Kept<MatrixX> jacobian_;  // transposed
  MatrixX dg_t_;
};

class SpeedConstraint : public ConstraintSet {
 public:
  SpeedConstraint(GaitEvaluationCache& cache, double speed) : cache_(cache), speed_(speed) {}
  std::string name() const override { return "speed"; }
  int size() const override { return 1; }
  void bounds(Eigen::Ref<VectorX> lower, Eigen::Ref<VectorX> upper) const override {
    lower.setZero();
    upper.setZero();
  }
  bool values(const VectorX& x, Eigen::Ref<VectorX> g) override {
    const GaitEvaluation<double>& e = cache_.values(toParameters(x));
    if (e.state[cache_.evaluator().layout()[kNoFallBack].offset] ==
        ConstraintState::NotComputed)
      return false;
    g(0) = e.speed - speed_;  // (3.50)
    return true;
  }
  bool jacobian(const VectorX& x, Eigen::Ref<MatrixX> jac) override {
    const GaitGradient& gr = cache_.gradient(toParameters(x));
    if (gr.value.state[cache_.evaluator().layout()[kNoFallBack].offset] ==
        ConstraintState::NotComputed)
      return false;
    jac.row(0) = gr.dspeed.transpose();
    return true;
  }

 private:
  GaitEvaluationCache& cache_;
  double speed_;
};

}  // namespace

double criterionValue(const GaitEvaluation<double>& e, Criterion c) {
  return c == Criterion::Torque ? e.C_Gamma : c == Criterion::Energy ? e.C_E : e.W;
}

const GaitParameters& criterionGradient(const GaitGradient& g, Criterion c) {
  return c == Criterion::Torque ? g.dC_Gamma : c == Criterion::Energy ? g.dC_E : g.dW;
}

const char* criterionName(Criterion c) {
  return c == Criterion::Torque ? "C_Gamma" : c == Criterion::Energy ? "C_E" : "W";
}

GaitParameters parameterScales(const Parameterisation& par) {
  GaitParameters s(kNumGaitParameters);
  // α, δ1, θ3, d, α, δ1, θ3, δ1, θ3, x2r, z2, α̇, δ1*, δ2*, δ1*, δ2*, T_DS
  s << 0.1, 0.1, 0.1, 0.05, 0.1, 0.1, 0.1, 0.1, 0.1, 0.05, 0.02, 0.2, 0.5, 0.5, 0.5, 0.5, 0.05;
  return extendPerParameter(s, par, {0.1, 0.1}, {0.1, 0.1});
}

VariableSet gaitVariables(const Model& m, const GaitParameters& initial,
                          const Parameterisation& par) {
  const JointLimits& jl = m.robot.limits;
  const double up = 0.5 * M_PI;
  GaitParameters lo(kNumGaitParameters), hi(kNumGaitParameters);
  lo << -1.2, jl.knee_min, up - 1.0, 0.05, -1.2, jl.knee_min, up - 1.0, jl.knee_min, up - 1.0,
      -0.8, 0.0, -10.0, -10.0, -10.0, -10.0, -10.0, 0.01;
  hi << 1.2, jl.knee_max, up + 1.0, 1.0, 1.2, jl.knee_max, up + 1.0, jl.knee_max, up + 1.0, 0.8,
      0.5, -0.01, 10.0, 10.0, 10.0, 10.0, 1.0;
  VariableSet v;
  v.names = par.names();
  // Extra SS points: δ3 (inter-leg angle) within ±π, δ4 within the knee limits.
  v.lower = extendPerParameter(lo, par, {-M_PI, jl.knee_min}, {jl.knee_min, up - 1.0});
  v.upper = extendPerParameter(hi, par, {M_PI, jl.knee_max}, {jl.knee_max, up + 1.0});
  v.initial = initial.cwiseMax(v.lower).cwiseMin(v.upper);
  // Entries the gait family determines (impact then single support) stay where they are.
  for (int i = 0; i < par.size(); ++i)
    if (!par.isUsed(i)) v.lower(i) = v.upper(i) = v.initial(i) = initial(i);
  return v;
}

std::unique_ptr<CostTerm> makeCriterionCost(GaitEvaluationCache& cache, Criterion criterion,
                                            double scale) {
  return std::make_unique<CriterionCost>(cache, criterion, scale);
}

std::unique_ptr<CostTerm> makeDistanceCost(const GaitParameters& reference,
                                           const Parameterisation& par) {
  return std::make_unique<DistanceCost>(reference, par);
}

double constraintScale(const ConstraintLayout& layout, const Model& m, int entry) {
  for (int g = 0; g < kNumConstraintGroups; ++g)
    if (entry < layout[g].offset + layout[g].count) return constraintGroupScale(g, m);
  return 1.0;
}

std::vector<int> hierarchyEntries(const ConstraintLayout& layout, int max_level) {
  std::vector<int> entries;
  for (int k = 0; k < layout.size(); ++k)
    if (layout.levelOf(k) <= max_level) entries.push_back(k);
  return entries;
}

std::unique_ptr<ConstraintSet> makeHierarchyConstraints(GaitEvaluationCache& cache,
                                                        const std::vector<int>& entries,
                                                        double interior, double level5_interior,
                                                        BetweenNodes between_nodes) {
  return std::make_unique<HierarchyConstraints>(cache, entries, interior, level5_interior,
                                                between_nodes);
}

std::unique_ptr<ConstraintSet> makeSpeedConstraint(GaitEvaluationCache& cache, double speed) {
  return std::make_unique<SpeedConstraint>(cache, speed);
}

}  // namespace gaitopt
