#pragma once
// Evaluator of Miossec's parameterised walking step: a constant description (model, options,
// grids, constraint layout) and the per-call evaluation of values, or values with the exact
// gradient with respect to the parameters (17 for the thesis, more for a richer one).
#include <Eigen/Core>
#include <algorithm>

#include "gaitopt/math/chebyshev.hpp"
#include "gaitopt/gait/evaluation.hpp"
#include "gaitopt/gait/options.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/model/model.hpp"

namespace gaitopt {

// Chebyshev grids of the phases: SS in α and DS in t for constraints and quadrature, the SS
// grid of W's and C_E's integrands (GaitOptions::criteria_refinement times finer, nested), and
// the grid of each DS quadrature piece.
struct GaitGrids {
  explicit GaitGrids(const GaitOptions& o)
      : ss(o.ss_nodes),
        ss_criteria(o.ss_nodes * o.criteria_refinement),
        ds(o.ds_nodes),
        ds_piece(o.ds_nodes) {}
  ChebyshevGrid ss, ss_criteria, ds, ds_piece;
};

// Values of one evaluation with first derivatives with respect to the parameters.
struct GaitGradient {
  GaitEvaluation<double> value;
  Eigen::MatrixXd dg;  // rows: constraints, columns: parameters
  GaitParameters dC_Gamma, dC_E, dW, dC_frott, dT_SS, dT_DS, dspeed;
  Eigen::MatrixXd dcriteria_kinks;  // rows: the AD pass's criteria_kinks (implicit functions)
  Eigen::MatrixXd dtorque_residuals;  // rows: value.torque_residuals
  Eigen::MatrixXd dss_joint_speeds;   // rows: value.ss_joint_speeds
  Eigen::MatrixXd dds_joint_speeds;   // rows: value.ds_joint_speeds
  std::vector<Eigen::MatrixXd> dds_piece_speeds;  // per DS piece: rows as value.ds_piece_speeds
  std::vector<Eigen::MatrixXd> dds_piece_g;  // per DS piece: rows as value.ds_piece_g
};

class GaitEvaluator {
 public:
  GaitEvaluator(const RobotParams& robot, const GaitOptions& options,
                const ModelOptions& model_options = {});
  // p must have options().parameterisation.size() entries (std::invalid_argument otherwise).
  GaitEvaluation<double> evaluate(const GaitParameters& p) const;
  // ds_piece_gradients: also the derivatives of the DS piece samples (dds_piece_g), needed only
  // by the DS between-node rows (gait/ds_interval_maxima.hpp) and most of a gradient's cost on
  // a step whose force split switches branch (bench_gait, "gradient, no DS pieces").
  GaitGradient evaluateWithGradient(const GaitParameters& p, bool ds_piece_gradients = true) const;
  int numParameters() const { return options_.parameterisation.size(); }
  // The same evaluator with W and C_E on another SS grid (GaitOptions::criteria_refinement,
  // ≥ 1); every other value is the same number.
  GaitEvaluator withCriteriaRefinement(int refinement) const;

  const Model& model() const { return model_; }
  const GaitOptions& options() const { return options_; }
  const ConstraintLayout& layout() const { return layout_; }
  const ChebyshevGrid& ssGrid() const { return grids_.ss; }
  const ChebyshevGrid& dsGrid() const { return grids_.ds; }
  const ChebyshevGrid& dsPieceGrid() const { return grids_.ds_piece; }

 private:
  Model model_;
  GaitOptions options_;
  ConstraintLayout layout_;
  GaitGrids grids_;

  template <class AD>
  GaitGradient gradientWith(const GaitParameters& p, bool ds_piece_gradients) const;
  void checkSize(const GaitParameters& p) const;
};

}  // namespace gaitopt
