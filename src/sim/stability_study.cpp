#include "gaitopt/sim/stability_study.hpp"

#include <cmath>
#include <vector>

#include "gaitopt/sim/impact_touchdown.hpp"
#include "gaitopt/sim/poincare_sensitivity.hpp"

namespace gaitopt {

namespace {

// Samples of one cycle step where the torque projection acts: 0 means the linearised field is
// the smooth unsaturated one.
int saturatedOnCycle(const GaitEvaluation<double>& e, const Model& model, const WalkRequest& base,
                     const Eigen::VectorXd& x, const TouchdownMap& td) {
  WalkRequest req = base;
  req.steps = 1;
  req.use_initial_state = true;
  req.q_init = x.head<5>();
  req.qd_init = x.tail<5>();
  const WalkResult r = simulateWalk(e, model, model, req, td);
  return r.steps.empty() ? 0 : r.steps.front().saturated_samples;
}

StabilityMargins stabilityMargins(const GaitEvaluation<double>& e, const RobotParams& robot,
                                  const GaitOptions& options, const ModelOptions& model_options,
                                  const Model& model, const WalkRequest& req, int steps) {
  StabilityMargins m;
  m.request.steps = steps;
  // A perturbed step lands with non-zero velocity, located by foot height: the touchdown map of
  // simulate (a DS gait's plastic impact with both feet held, else the algebraic rigid impact),
  // except that an impact lifting the rear foot starts the next SS at once (DS skipped).
  m.impact_model = resolvedImpactModel(options, "auto");
  const double mu = options.friction_coefficient;
  const TouchdownMap td = m.impact_model == "double_support"
                              ? doubleSupportTouchdown(mu, true)
                              : gaitTouchdown(options, m.impact_model, mu);
  m.push_forward = largestPush(e, model, req, 1, m.request, td);
  m.push_backward = largestPush(e, model, req, -1, m.request, td);
  m.trunk_payload = largestPayload(e, robot, model_options, req, m.request, td);
  m.slope_up = largestSlope(e, model, req, 1, m.request, td);
  m.slope_down = largestSlope(e, model, req, -1, m.request, td);
  return m;
}

// Fig. 4.5's grid: α̇_fDS of the cycle scaled by 1 ± range.
std::vector<double> dsZoneGrid(const GaitMotion<double>& motion, double range, int points) {
  std::vector<double> grid;
  for (int i = 0; i < points; ++i)
    grid.push_back(motion.ds_alpha(motion.T_DS).first *
                   (1.0 + range * (2.0 * i / (points - 1) - 1.0)));
  return grid;
}

}  // namespace

const char* toString(PoincareJacobianMethod m) {
  return m == PoincareJacobianMethod::Sensitivity ? "sensitivity" : "fd";
}

StabilityStudy studyStability(const GaitEvaluation<double>& e, const RobotParams& robot,
                              const GaitOptions& options, const ModelOptions& model_options,
                              const StabilityRequest& request) {
  const Model model = buildModel(robot, model_options);
  WalkRequest req;
  req.bandwidth = request.bandwidth;
  req.ds_control = request.ds_control;
  configureForGait(options, req);
  // The map's noise must stay far below the FD step.
  req.tolerances.relative = 1e-12;
  req.tolerances.absolute = 1e-14;
  // The linearisation needs a smooth field: the unsaturated controller (the projection on
  // the torque limits is non-smooth); margins and the saturation count use the projection.
  WalkRequest analysis = req;
  analysis.torque_limits = false;
  // A zero-velocity landing's foot height is tangent to the ground at α_fSS (no transversal
  // crossing for the saltation matrix): the analysis locates its touchdown by α, impulse-free.
  const bool impact_landing = options.parameterisation.landsWithImpact();
  analysis.touchdown_by_foot_height = impact_landing;
  analysis.hold_references_past_fss = false;
  const TouchdownMap td =
      gaitTouchdown(options, impact_landing ? "auto" : "none", options.friction_coefficient);
  // The map of the difference Jacobian and of the power iteration keeps the feet on the ground,
  // as the variational equations do: a cycle planned with a friction cone active (measured: the
  // stance foot of configs/gait/default_impact.yaml before touchdown) slips on one side of any
  // perturbation. The margins walk on the ground's friction.
  WalkRequest held = analysis;
  held.detect_slip = false;
  const StepMap P = walkingStepMap(e, model, model, held, td);
  int stage = 0;
  const auto starting = [&](const char* name) {
    if (request.on_stage) request.on_stage(name, ++stage, kStabilityStages);
  };
  StabilityStudy s{};
  s.fixed_point = walkingCycleState(e.motion);
  const Eigen::VectorXd h = Eigen::VectorXd::Constant(10, request.fd_step);
  starting("Poincare linearisation");
  // The variational equations of the {ss_points: 11} C&A impact gait take 10⁵ CVODE steps
  // before its touchdown (measured); the map itself integrates, so its central differences give
  // the Jacobian there.
  s.linearisation =
      request.jacobian == PoincareJacobianMethod::FiniteDifference
          ? linearisePoincare(P, s.fixed_point, h)
          : linearisePoincareOrDifferences(
                [&] {
                  return linearisePoincareBySensitivity(e, model, model, analysis,
                                                        s.fixed_point, td);
                },
                P, s.fixed_point, h, s.jacobian_fallback);
  s.jacobian_method = s.jacobian_fallback.empty() ? request.jacobian
                                                  : PoincareJacobianMethod::FiniteDifference;
  starting("power iteration");
  s.power_estimate =
      powerIteration(P, s.fixed_point, h, request.power_iterations, s.power_vector);
  s.dominant_modulus = std::abs(s.linearisation.eigenvalues(0));
  s.stable = s.dominant_modulus < 1.0;
  s.stable_cycle = s.stable && s.linearisation.fixed_point_residual < 1e-6;
  starting("zero-dynamics map");
  ZeroDynamicsRequest zr;
  zr.range = request.map_range;
  zr.points = request.map_points;
  zr.touchdown = td;
  s.zero_dynamics = studyZeroDynamics(e, model, model, analysis, zr);
  s.zero_dynamics_max_steps = zr.max_steps;
  s.has_double_support = options.parameterisation.hasDoubleSupport();
  s.ds_limits = dsLimitsOf(options);
  starting("double-support convergence zone");
  if (s.has_double_support)
    s.ds_zone = studyDsZone(model, e.motion, s.ds_limits,
                            dsZoneGrid(e.motion, request.ds_range, request.ds_points));
  starting("torque saturation on the cycle");
  s.saturated_samples_on_cycle =
      saturatedOnCycle(e, model, req, s.fixed_point,
                       gaitTouchdown(options, "auto", options.friction_coefficient));
  starting("margins: push, payload, slope");
  s.margins = stabilityMargins(e, robot, options, model_options, model, req, request.margin_steps);
  return s;
}

}  // namespace gaitopt
