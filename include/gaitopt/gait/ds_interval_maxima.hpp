#pragma once
// The DS level-5 constraints (3.42), (3.43), (3.46)–(3.48) between the DS grid nodes. Their
// values kink where the force split switches branch (ds_switch_times), so one interpolant of
// the DS node values oscillates there; between two switch times (a DS piece) they are smooth
// and the piece's own Chebyshev samples (GaitEvaluation::ds_piece_g) interpolate them
// spectrally. The maximum of an entry's sequence between DS nodes j and j + 1 is the largest
// of the two node values, the values at the switch times inside (piece ends) and the maxima of
// the piece interpolants on the pieces' parts of the interval. Without a switch the DS node
// values are the one piece. The torque rows of joints with Coulomb friction are split
// (gait/coulomb_split.hpp): a piece's maximum is that of h + Γs tanh(w/ε).
#include <vector>

#include "gaitopt/gait/coulomb_split.hpp"
#include "gaitopt/gait/evaluator.hpp"

namespace gaitopt {

// Where an interval's maximum is: at a DS node (its layout entry), or at s of a piece's grid
// (s = ±1: a piece end, i.e. a switch time).
struct DsIntervalMaximum {
  int node = 0;    // the DS node, when piece < 0
  int piece = -1;
  double s = 0.0;
  double value = 0.0;
};

class DsIntervalMaxima {
 public:
  explicit DsIntervalMaxima(const GaitEvaluator& evaluator);
  // The maxima of every DS level-5 sequence over every interval; false when the motion or a
  // piece value is missing or not finite.
  bool update(const GaitEvaluation<double>& e);
  // Of the sequence of group's entry `sub` within a node, between DS nodes interval and
  // interval + 1 (0 ≤ interval < ds_nodes).
  const DsIntervalMaximum& maximum(int group, int sub, int interval) const;
  // Its gradient by the envelope theorem: the node entry's, or Σ_m l_m(s*) ∇g_m over the
  // piece's samples; at a switch time the piece end's, which carries the switch time's
  // derivative (the constraint is continuous across the switch).
  Eigen::VectorXd gradient(int group, int sub, int interval, const GaitGradient& g) const;

 private:
  struct Sequence {
    int group, sub;
  };
  // Block-relative index (ConstraintLayout::dsMotionOffset) of a sequence's entry at node k.
  int entry(const Sequence& q, int k) const;
  int sequenceIndex(int group, int sub) const;
  void maximiseInterval(int q, int interval, const std::vector<Eigen::MatrixXd>& values,
                        const std::vector<Eigen::MatrixXd>& slopes,
                        const std::vector<double>& bounds, const std::vector<double>& node_t,
                        const GaitEvaluation<double>& e);
  // ω_j of piece p's sample k (without a switch: DS node k).
  static double speedAt(const GaitEvaluation<double>& e, int p, int k, int joint);
  // The split sequences' node values of piece p made their smooth parts h, and σω beside them.
  void splitPiece(const GaitEvaluation<double>& e, int p, Eigen::MatrixXd& values);
  Eigen::VectorXd splitGradient(int q, const DsIntervalMaximum& m, const GaitGradient& g) const;

  const GaitEvaluator& ev_;
  std::vector<Sequence> sequences_;
  std::vector<CoulombSplit> splits_;           // [sequence]; coulomb 0: not split
  std::vector<Eigen::MatrixXd> speeds_;        // [piece]: σω at its samples, [sample][sequence]
  std::vector<std::vector<DsIntervalMaximum>> maxima_;  // [sequence][interval]
};

}  // namespace gaitopt
