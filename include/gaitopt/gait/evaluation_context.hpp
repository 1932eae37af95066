#pragma once
// State shared by the stages of one step evaluation (gait/evaluator_impl.hpp): the constant
// description, the parameters and the evaluation being filled, with the hierarchy bookkeeping
// (the state of an entry from the lowest violated level below it).
#include "gaitopt/gait/constraints.hpp"
#include "gaitopt/gait/evaluation.hpp"
#include "gaitopt/gait/options.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/math/chebyshev.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt::detail {

template <class S> struct EvalContext {
  const Model& model;
  const GaitOptions& options;
  const ConstraintLayout& layout;
  const ChebyshevGrid& ss_grid;
  const ChebyshevGrid& ss_criteria_grid;  // W and C_E in the SS (GaitGrids::ss_criteria)
  const ChebyshevGrid& ds_grid;
  const ChebyshevGrid& piece_grid;
  const GaitVector<S>& p;
  GaitEvaluation<S>& out;
  const DsPieces* known_pieces;  // DS quadrature pieces found by a double pass, or null
  bool record_pieces;            // GaitEvaluation::ds_piece_g wanted

  void set(int group, int index, const S& value, ConstraintState state) {
    const int k = layout[group].offset + index;
    out.g[k] = value;
    out.state[k] = state;
  }
  // Lowest level ≤ max_level with a violated computed entry, or −1.
  int lowestViolated(int max_level) const {
    int lowest = -1;
    for (int k = 0; k < layout.size(); ++k)
      if (out.state[k] != ConstraintState::NotComputed && layout.levelOf(k) <= max_level &&
          valueOf(out.g[k]) > 0.0 && (lowest < 0 || layout.levelOf(k) < lowest))
        lowest = layout.levelOf(k);
    return lowest;
  }
  ConstraintState stateAbove(int level) const {
    const int failed = lowestViolated(level);
    return failed < 0 ? ConstraintState::Defined : ConstraintState::Extended;
  }
};

}  // namespace gaitopt::detail
