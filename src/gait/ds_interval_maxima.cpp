#include "gaitopt/gait/ds_interval_maxima.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gaitopt/math/chebyshev_maxima.hpp"

namespace gaitopt {
namespace {

// Grid coordinate of time t on a piece [a, b] (mappedNodes: s = +1 at a, −1 at b).
double pieceCoordinate(double t, double a, double b) {
  return std::clamp(1.0 - 2.0 * (t - a) / (b - a), -1.0, 1.0);
}

}  // namespace

DsIntervalMaxima::DsIntervalMaxima(const GaitEvaluator& ev) : ev_(ev) {
  const ConstraintLayout& layout = ev.layout();
  for (int id = 0; id < kNumConstraintGroups; ++id) {
    const ConstraintGroup& g = layout[id];
    if (g.phase != ConstraintPhase::DoubleSupport || g.level != 5) continue;  // the DS motion's
    for (int sub = 0; sub < g.per_point; ++sub) {
      sequences_.push_back({id, sub});
      splits_.push_back(coulombSplit(ev.model(), id, sub));
    }
  }
}

int DsIntervalMaxima::entry(const Sequence& q, int k) const {
  const ConstraintGroup& g = ev_.layout()[q.group];
  return g.offset - ev_.layout().dsMotionOffset() + k * g.per_point + q.sub;
}

int DsIntervalMaxima::sequenceIndex(int group, int sub) const {
  int q = 0;
  while (sequences_[q].group != group || sequences_[q].sub != sub) ++q;
  return q;
}

bool DsIntervalMaxima::update(const GaitEvaluation<double>& e) {
  const ChebyshevGrid& grid = ev_.dsPieceGrid();
  const int first = ev_.layout().dsMotionOffset();
  if (!e.motion_computed || sequences_.empty()) return false;
  const double T = e.motion.T_DS;
  // Without a switch the DS node values are the one piece (the DS grid is the piece grid).
  const bool split = !e.ds_piece_g.empty();
  const std::vector<double> bounds = split ? e.ds_piece_bounds : std::vector<double>{0.0, T};
  const int pieces = static_cast<int>(bounds.size()) - 1;
  std::vector<Eigen::MatrixXd> values(pieces), slopes(pieces);
  speeds_.assign(pieces, Eigen::MatrixXd());
  for (int p = 0; p < pieces; ++p) {
    values[p].resize(grid.size(), static_cast<int>(sequences_.size()));
    for (int q = 0; q < values[p].cols(); ++q)
      for (int k = 0; k < grid.size(); ++k) {
        const int i = entry(sequences_[q], k);
        values[p](k, q) = split ? e.ds_piece_g[p][i] : e.g[first + i];
      }
    if (!values[p].allFinite()) return false;
    splitPiece(e, p, values[p]);
    slopes[p] = grid.differentiation() * values[p];
  }
  std::vector<double> node_t(ev_.dsGrid().size());
  for (int k = 0; k < ev_.dsGrid().size(); ++k)
    node_t[k] = 0.5 * (1.0 - ev_.dsGrid().nodes()[k]) * T;
  maxima_.assign(sequences_.size(), std::vector<DsIntervalMaximum>(ev_.dsGrid().degree()));
  for (int q = 0; q < static_cast<int>(sequences_.size()); ++q)
    for (int j = 0; j < ev_.dsGrid().degree(); ++j)
      maximiseInterval(q, j, values, slopes, bounds, node_t, e);
  return true;
}

// The larger node value, then every piece overlapping [t_j, t_{j+1}]: its interpolant's
// maximum on the overlap counts unless it sits at an overlap end that is a DS node (the node's
// exact value stands there).
void DsIntervalMaxima::maximiseInterval(int q, int j, const std::vector<Eigen::MatrixXd>& values,
                                        const std::vector<Eigen::MatrixXd>& slopes,
                                        const std::vector<double>& bounds,
                                        const std::vector<double>& node_t,
                                        const GaitEvaluation<double>& e) {
  const int first = ev_.layout().dsMotionOffset();
  const double g0 = e.g[first + entry(sequences_[q], j)];
  const double g1 = e.g[first + entry(sequences_[q], j + 1)];
  DsIntervalMaximum best = g0 >= g1 ? DsIntervalMaximum{j, -1, 0.0, g0}
                                    : DsIntervalMaximum{j + 1, -1, 0.0, g1};
  const double lo = node_t[j], hi = node_t[j + 1];
  for (int p = 0; p + 1 < static_cast<int>(bounds.size()); ++p) {
    const double a = bounds[p], b = bounds[p + 1];
    if (!(b > a) || a >= hi || b <= lo) continue;
    const double s_lo = pieceCoordinate(std::max(a, lo), a, b);  // the earlier end: larger s
    const double s_hi = pieceCoordinate(std::min(b, hi), a, b);
    const InterpolantMaximum m =
        splits_[q].coulomb != 0.0
            ? SplitRow(ev_.dsPieceGrid(), splits_[q], values[p].col(q), speeds_[p].col(q))
                  .maximumOn(s_hi, s_lo)
            : maximumOn(ev_.dsPieceGrid(), values[p].col(q), slopes[p].col(q), s_hi, s_lo);
    const bool at_node = (m.s == s_lo && a <= lo) || (m.s == s_hi && b >= hi);
    if (!at_node && m.value > best.value) best = {0, p, m.s, m.value};
  }
  maxima_[q][j] = best;
}

double DsIntervalMaxima::speedAt(const GaitEvaluation<double>& e, int p, int k, int joint) {
  return e.ds_piece_g.empty() ? e.ds_joint_speeds[4 * k + joint]
                              : e.ds_piece_speeds[p][4 * k + joint];
}

void DsIntervalMaxima::splitPiece(const GaitEvaluation<double>& e, int p,
                                  Eigen::MatrixXd& values) {
  speeds_[p] = Eigen::MatrixXd::Zero(values.rows(), values.cols());
  for (int q = 0; q < values.cols(); ++q) {
    const CoulombSplit& c = splits_[q];
    if (c.coulomb == 0.0) continue;
    for (int k = 0; k < values.rows(); ++k) {
      const double omega = speedAt(e, p, k, c.joint);
      values(k, q) -= c.term(omega);
      speeds_[p](k, q) = c.sigma * omega;
    }
  }
}

const DsIntervalMaximum& DsIntervalMaxima::maximum(int group, int sub, int interval) const {
  return maxima_[sequenceIndex(group, sub)][interval];
}

Eigen::VectorXd DsIntervalMaxima::gradient(int group, int sub, int interval,
                                           const GaitGradient& g) const {
  const int q = sequenceIndex(group, sub);
  const DsIntervalMaximum& m = maxima_[q][interval];
  const int first = ev_.layout().dsMotionOffset();
  if (m.piece < 0) return g.dg.row(first + entry(sequences_[q], m.node)).transpose();
  const bool split = !g.value.ds_piece_g.empty();
  if (split && g.dds_piece_g.size() != g.value.ds_piece_g.size())
    throw std::logic_error("DS interval maxima: a gradient without the DS piece derivatives "
                           "(evaluateWithGradient's ds_piece_gradients)");
  if (splits_[q].coulomb != 0.0) return splitGradient(q, m, g);
  const Eigen::VectorXd l = lagrangeBasis(ev_.dsPieceGrid(), m.s);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(g.dg.cols());
  for (int k = 0; k < l.size(); ++k) {
    const int i = entry(sequences_[q], k);
    out += l[k] * (split ? g.dds_piece_g[m.piece].row(i) : g.dg.row(first + i)).transpose();
  }
  return out;
}

// Envelope theorem on h + Γs tanh(w/ε) at the piece's s*: Σ_k l_k (∇g_k − term'(ω_k) ∇ω_k)
// + σ row'(w(s*)) Σ_k l_k ∇ω_k.
Eigen::VectorXd DsIntervalMaxima::splitGradient(int q, const DsIntervalMaximum& m,
                                                const GaitGradient& g) const {
  const CoulombSplit& c = splits_[q];
  const bool split = !g.value.ds_piece_g.empty();
  const int first = ev_.layout().dsMotionOffset();
  const Eigen::VectorXd l = lagrangeBasis(ev_.dsPieceGrid(), m.s);
  double w = 0.0;
  for (int k = 0; k < l.size(); ++k) w += l[k] * c.sigma * speedAt(g.value, m.piece, k, c.joint);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(g.dg.cols());
  for (int k = 0; k < l.size(); ++k) {
    const int i = entry(sequences_[q], k);
    const auto dg = split ? g.dds_piece_g[m.piece].row(i) : g.dg.row(first + i);
    const auto domega = split ? g.dds_piece_speeds[m.piece].row(4 * k + c.joint)
                              : g.dds_joint_speeds.row(4 * k + c.joint);
    const double omega = speedAt(g.value, m.piece, k, c.joint);
    out += l[k] * (dg - c.sigma * (c.rowSlope(omega) - c.rowSlope(w)) * domega).transpose();
  }
  return out;
}

}  // namespace gaitopt
