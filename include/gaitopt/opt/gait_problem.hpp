#pragma once
// The walking-step optimisation problem as named pieces over the 17 gait parameters: the
// criterion, a weighted distance (for projections onto lower hierarchy levels), the hierarchy's
// constraints up to a chosen level, and the walking speed (3.50).
#include <memory>

#include "gaitopt/opt/evaluation_cache.hpp"
#include "gaitopt/opt/nlp_problem.hpp"

namespace gaitopt {

enum class Criterion { Torque, Energy, Work };  // C_Γ (3.28), C_E (3.32), W (3.147)

const char* criterionName(Criterion c);
double criterionValue(const GaitEvaluation<double>& e, Criterion c);
const GaitParameters& criterionGradient(const GaitGradient& g, Criterion c);

// Box bounds that keep the parameters in the physically meaningful range (documented in the
// docs/commands/optimize.md): knees within the joint limits, trunk within 1 rad of upright, 0.05 ≤ d ≤ 1 m, ...
VariableSet gaitVariables(const Model& model, const GaitParameters& initial,
                          const Parameterisation& parameterisation);

// Typical magnitude of one parameter, used to weigh distances in parameter space (§3.4.2 leaves
// the norm open: parameters mix rad, m, rad/s and s).
GaitParameters parameterScales(const Parameterisation& parameterisation);

std::unique_ptr<CostTerm> makeCriterionCost(GaitEvaluationCache& cache, Criterion criterion,
                                            double scale);
std::unique_ptr<CostTerm> makeDistanceCost(const GaitParameters& reference,
                                           const Parameterisation& parameterisation);
// constraintGroupScale (gait/constraints.hpp) of the group holding a layout entry.
double constraintScale(const ConstraintLayout& layout, const Model& model, int entry);
// Layout entries of every level ≤ max_level.
std::vector<int> hierarchyEntries(const ConstraintLayout& layout, int max_level);
// Which phase-wise rows are maxima between the nodes; the others are node rows.
enum class BetweenNodes { None, SingleSupport, Both };

// The given layout entries as g / scale ≤ −interior for levels 0–4 (the evaluator fails them
// at g > 0) and ≤ −level5_interior for level 5. Between the nodes, the row of a phase-wise
// entry at node j is the maximum over [s_{j+1}, s_j] of the Chebyshev interpolant of its
// sequence (math/chebyshev_maxima.hpp), for the DS level-5 groups of its pieces' interpolants
// (gait/ds_interval_maxima.hpp): the semi-infinite constraint held on the whole phase.
std::unique_ptr<ConstraintSet> makeHierarchyConstraints(
    GaitEvaluationCache& cache, const std::vector<int>& entries, double interior = 1e-6,
    double level5_interior = 0.0, BetweenNodes between_nodes = BetweenNodes::Both);
std::unique_ptr<ConstraintSet> makeSpeedConstraint(GaitEvaluationCache& cache, double speed);

}  // namespace gaitopt
