#pragma once
// Result of evaluating one walking step: the constraint vector with its per-entry state, the
// criteria, and the motion (polynomials and zero-dynamics solution) from which the trajectory is
// sampled. Templated so the same evaluation runs on double and on an AD scalar.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "gaitopt/gait/constraints.hpp"
#include "gaitopt/gait/impact_landing.hpp"
#include "gaitopt/gait/path_curve.hpp"
#include "gaitopt/gait/polynomials.hpp"
#include "gaitopt/math/types.hpp"

namespace gaitopt {

template <class S> struct GaitMotion {
  S d = S(0.0), T_DS = S(0.0), T_SS = S(0.0);
  Vector5<S> q_iDS, q_fDS, q_iSS, q_fSS;
  S alpha_iSS = S(0.0), alpha_fSS = S(0.0);
  std::vector<Vector5<S>> q_ss_points;  // interior SS configurations (α_int for the thesis)
  std::array<PathCurve<S>, 4> ss_path;  // δ1..δ4 as functions of α (3.2)
  PathCurve<S> ds_delta1, ds_delta2;    // δ1, δ2 as functions of α (3.3)
  LocalPolynomial<S> ds_alpha;                // α as a function of t (3.4)
  S alphadot_iSS = S(0.0);                 // after the saturation (3.56)
  S f_iSS = S(0.0);                        // max(f(α_iSS), f_min)
  S alphadot_fSS = S(0.0), kappa = S(0.0);
  Eigen::Matrix<S, Eigen::Dynamic, 1> ss_phi, ss_time;  // Φ and t at the SS nodes
  Eigen::Matrix<S, Eigen::Dynamic, 1> ss_alphadot, ss_alphaddot;  // (3.15), (3.16) there
  LandingImpact<S> landing;  // a landing with impact only
};

// Double-support quadrature pieces, split where the force-distribution branch changes; each
// piece is integrated with its own branch (gait/ds_force_distribution.hpp).
struct DsPieces {
  std::vector<double> switch_times;  // from DS start [s]
  std::vector<int> switch_function;  // which switching function vanishes there
  std::vector<double> switch_rate;   // its time derivative there [1/s × its unit]
  std::vector<int> branches;         // one per piece: switch_times.size() + 1
};

template <class S> struct GaitEvaluation {
  std::vector<S> g;
  std::vector<ConstraintState> state;
  int failed_level = -1;         // lowest level with a violated constraint; −1: none
  bool motion_computed = false;  // criteria and level-5 values exist (possibly extended)
  bool numerically_undefined = false;  // the motion overflowed; reported as failed at level 4
  S C_Gamma = S(0.0), C_E = S(0.0), W = S(0.0), C_frott = S(0.0);
  S T_SS = S(0.0), T_DS = S(0.0), step_length = S(0.0), speed = S(0.0), alphadot_fSS = S(0.0);
  GaitMotion<S> motion;
  DsPieces ds_pieces;
  // The DS level-5 entries sampled on each DS piece's own grid (GaitGrids::ds_piece) with the
  // piece's branch, where they are smooth: one vector per piece, node k's entries at the
  // offsets of DS node k in the layout's DS level-5 block (ConstraintLayout::dsMotionOffset);
  // and the pieces' bounds [s from DS start], one more than pieces. Empty without a switch.
  std::vector<std::vector<S>> ds_piece_g;
  std::vector<double> ds_piece_bounds;
  // Where the quadrature of W and C_E is split: the roots of the Γ*_j ω_j and of the electrical
  // power, the SS ones first (α [rad], the first ss_criteria_kinks entries), then the DS ones
  // (t from the DS start [s]), each phase in time order.
  std::vector<S> criteria_kinks;
  int ss_criteria_kinks = 0;
  // C_Γ as a sum of squares, C_Γ = Σ r_i² (3.28): √(quadrature weight / d) times each torque
  // Γ*_j / √|phase rate| at the SS nodes, then at the DS (or DS piece) nodes. Their Jacobian J
  // gives the Gauss–Newton Hessian 2 JᵀJ of C_Γ.
  std::vector<S> torque_residuals;
  // The joint-side speeds ω (1.20) at the SS nodes, ω_j of node k at 4k + j: the turn of the
  // Coulomb friction's smooth sign with ω (1.21) is what the SS torque rows between the nodes
  // take apart (gait/coulomb_split.hpp).
  std::vector<S> ss_joint_speeds;
  // The same at the DS nodes, and at each DS piece's samples (one vector per piece, as
  // ds_piece_g, when that is recorded).
  std::vector<S> ds_joint_speeds;
  std::vector<std::vector<S>> ds_piece_speeds;

  // Defined in the thesis' sense: every level below the criterion's (0–4) holds.
  bool defined() const { return failed_level < 0 || failed_level >= 5; }
};

}  // namespace gaitopt
