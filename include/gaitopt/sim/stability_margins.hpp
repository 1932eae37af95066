#pragma once
// Robustness margins of the closed-loop gait beyond the thesis, each found by bisection on the
// hybrid simulation (sim/hybrid_walk.hpp):
// - push: the largest horizontal velocity change Δv of the hip, given by an impulsive horizontal
//   force at the hip at mid single support (α halfway from α_iSS to α_fSS on the cycle),
//   forward (Δv > 0) or backward, after which the walk is back on the cycle within N steps;
// - payload: the largest point mass added at the trunk's centre of mass of the plant (the
//   controller keeps the nominal model) with which the robot walks N steps and settles on a
//   cycle (the real RABBIT walked with +10 kg on its torso);
// - slope: the steepest ground, up or down, inclined from the first stance foot on, on which
//   the robot walks N steps (the controller does not know the slope: it walks upright).

#include <string>

#include "gaitopt/model/robot_params.hpp"
#include "gaitopt/sim/hybrid_walk.hpp"

namespace gaitopt {

struct MarginRequest {
  int steps = 5;               // recovery / walking steps
  double tolerance = 1e-3;     // ‖x − x*‖∞ at the last SS start (push); |Δα̇_iSS| of the last
                               // two steps (payload) [rad, rad/s]
  double push_upper = 2.0;     // [m/s] bracket of the bisection
  double push_resolution = 1e-3;     // [m/s]
  double payload_upper = 40.0;       // [kg]
  double payload_resolution = 0.05;  // [kg]
  double slope_upper = 0.3;          // [rad]
  double slope_resolution = 1e-3;    // [rad]
};

struct Margin {
  double value = 0.0;       // largest value passing, to within `resolution`
  double resolution = 0.0;
  bool bracket_reached = false;  // the upper bracket itself passes (value = upper)
  std::string limit;  // why value + resolution fails
};

// Walks `steps` steps after a hip push Δv at mid SS; true when back on the cycle. `why` says
// how it failed.
bool pushRecovered(const GaitEvaluation<double>& evaluation, const Model& model,
                   const WalkRequest& base, double dv, const MarginRequest& request,
                   const TouchdownMap& touchdown, std::string& why);

// direction +1: forward push, −1: backward.
Margin largestPush(const GaitEvaluation<double>& evaluation, const Model& model,
                   const WalkRequest& base, int direction, const MarginRequest& request,
                   const TouchdownMap& touchdown = impulseFreeTouchdown());

bool payloadTolerated(const GaitEvaluation<double>& evaluation, const RobotParams& robot,
                      const ModelOptions& options, const WalkRequest& base, double mass,
                      const MarginRequest& request, const TouchdownMap& touchdown,
                      std::string& why);

Margin largestPayload(const GaitEvaluation<double>& evaluation, const RobotParams& robot,
                      const ModelOptions& options, const WalkRequest& base,
                      const MarginRequest& request,
                      const TouchdownMap& touchdown = impulseFreeTouchdown());

// Walks `steps` steps from the cycle's SS start on ground inclined by `slope` [rad].
bool slopeWalked(const GaitEvaluation<double>& evaluation, const Model& model,
                 const WalkRequest& base, double slope, const MarginRequest& request,
                 const TouchdownMap& touchdown, std::string& why);

// direction +1: uphill, −1: downhill.
Margin largestSlope(const GaitEvaluation<double>& evaluation, const Model& model,
                    const WalkRequest& base, int direction, const MarginRequest& request,
                    const TouchdownMap& touchdown = impulseFreeTouchdown());

}  // namespace gaitopt
