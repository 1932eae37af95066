#pragma once
// Shared fixtures for the gait tests: a DEFINED step of the default robot (levels 0–4 hold;
// some level-5 constraints are violated, which does not matter for consistency tests) and the
// evaluator of the default robot with the options those steps were found with.
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/options.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "test_support.hpp"

namespace gaitopt::test {

// In the order of kGaitParameterNames: alpha_iDS, delta1_iDS, theta3_iDS, d, alpha_fDS,
// delta1_fDS, theta3_fDS, delta1_int, theta3_int, x2r_int, z2_int, alphadot_iSS, delta1s_iSS,
// delta2s_iSS, delta1s_fSS, delta2s_fSS, T_DS.
inline GaitParameters definedStep() {
  GaitParameters p(kNumGaitParameters);
  p << -0.044819, -2.593492, 1.520796, 0.35, -0.190837, -2.495513, 1.520796, -2.445513,
      1.520796, 0.0, 0.06, -0.9, 0.3, 0.3, 0.3, 0.3, 0.12;
  return p;
}

// The C_Gamma-optimal step of the default robot at 0.5 m/s (gaitopt optimize, nlopt_slsqp,
// C_Gamma = 9122.63 N²·m·s): every constraint holds.
inline GaitParameters optimalStep() {
  GaitParameters p(kNumGaitParameters);
  p << 0.0192773503, -2.65033763, 1.38578892, 0.30881926, -0.0335627699, -2.6061693, 1.37072667,
      -2.56752143, 1.37135822, 0.0589803378, 0.0297501461, -1.02042521, -0.399879997,
      0.157357809, 0.602535363, 1.13725619, 0.037402875;
  return p;
}

// The options the hard-coded steps above were found and measured with: the defaults, but
// viscous joint friction only (dry_friction: false). With the robot's Coulomb friction the
// optimal step needs 16.4 N·m more than the torque envelope at the stance hip.
inline GaitOptions viscousOptions() {
  GaitOptions o;
  o.dry_friction = false;
  return o;
}

inline GaitEvaluator defaultGaitEvaluator(const GaitOptions& options = viscousOptions()) {
  return GaitEvaluator(robotFile("rabbit_miossec"), options);
}

}  // namespace gaitopt::test
