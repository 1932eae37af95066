#pragma once
// One step evaluation shared by every cost term and constraint set of an optimisation problem
// at the current point (the solver asks for f, ∇f, g and ∂g separately at the same x).
#include <optional>

#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/feasibility.hpp"

namespace gaitopt {

enum class GradientMode {
  Exact,            // forward-mode AD through the evaluation
  FiniteDifference  // central differences of the values, for comparison (§3.6.4)
};

class GaitEvaluationCache {
 public:
  explicit GaitEvaluationCache(const GaitEvaluator& evaluator,
                               GradientMode mode = GradientMode::Exact)
      : evaluator_(evaluator), mode_(mode) {}
  const GaitEvaluator& evaluator() const { return evaluator_; }
  const GaitEvaluation<double>& values(const GaitParameters& p);
  const GaitGradient& gradient(const GaitParameters& p);
  // Whether values(p) answers with the gradient pass's values (kept at p), not a plain pass.
  bool holdsGradient(const GaitParameters& p) const { return gradient_at_ && *gradient_at_ == p; }
  // The 10× finer check between the nodes (gait/feasibility.hpp) at p, kept for the last point
  // asked (an optimisation checks its end point several times).
  const BetweenNodesCheck& betweenNodes(const GaitParameters& p);
  // Whether gradients carry the DS piece samples' derivatives (set by the constraint set that
  // needs them, opt/gait_problem.cpp); off by default, they are the costly part of a gradient.
  void setDsPieceGradients(bool on);
  int valueEvaluations() const { return value_count_; }
  int gradientEvaluations() const { return gradient_count_; }

 private:
  GaitGradient finiteDifferenceGradient(const GaitParameters& p);

  const GaitEvaluator& evaluator_;
  GradientMode mode_;
  bool ds_piece_gradients_ = false;
  std::optional<GaitParameters> value_at_, gradient_at_;
  GaitEvaluation<double> values_;
  GaitGradient gradient_;
  std::optional<GaitParameters> between_nodes_at_;
  BetweenNodesCheck between_nodes_;
  int value_count_ = 0, gradient_count_ = 0;
};

}  // namespace gaitopt
