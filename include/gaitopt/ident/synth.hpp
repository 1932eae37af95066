#pragma once
// Synthetic "measured" walking data from a TRUE model = a robot plus named effects
// (ident/effects.hpp): consecutive steps alternating the physical stance leg, each a small
// seeded random variation of a gait (excitation). Each step is the gait's double support
// (prescribed in time, leg 1 in front) then its single support. Single support follows the
// TRUE model's zero dynamics from the gait's initial α̇ (integrated here, so that a ground
// slope — gravity tilted in the gait's frame — is included); torques and reactions come from
// the TRUE model's inverse dynamics, in double support with the torque-optimal split
// R2x = argmin ‖Γ*‖² = Kᵀ J / Kᵀ K of (3.62). The centres of pressure: the point feet in double
// support, the rolling contact of a rocker foot in single support. Then the sensor effects,
// encoder quantisation, torque, force and centre-of-pressure noise.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "gaitopt/gait/options.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/ident/admissible_range.hpp"
#include "gaitopt/ident/effects.hpp"
#include "gaitopt/ident/measured_data.hpp"

namespace gaitopt {

// Effects OUTSIDE the library of `diagnose` (ident/effects.hpp), physically motivated, to
// test that a diagnosis reports what it cannot explain instead of a confident wrong cause:
//  - knee_centre@KNEE = c [m/rad]: the knee is not a pure hinge, its centre of rotation moves
//    along the femur as the knee flexes (rolling–gliding condyles; the instantaneous axis moves
//    about 2 cm over 70° of flexion): ∂p_K/∂q_k = c (1 + flexion / 1 rad) along the femur. Its
//    generalised force F_K · ∂p_K/∂q_k — F_K the force the femur exerts on the tibia, from the
//    ground reaction and the tibia's weight (the tibia's own acceleration neglected) — is added
//    to that knee's torque. First order in the excursion: the angles stay the revolute knee's.
//  - joint_compliance@JOINT = K [N·m/rad]: series elasticity between the motor and the link; the
//    encoder reads the link angle + Γ*/K.
//  - ground_compliance = K [N/m]: the ground under the stance foot is a vertical spring, the
//    foot sinks by s = R1z/K in single support. The ankle's acceleration a_A = (0, −s̈) adds
//    M a_A to the ground reaction and, in the frame translating with the ankle (as for the rocker
//    foot, model/rocker_foot.hpp), J_bᵀ a_A to the joint torques. First order in the sinking:
//    the angles stay the rigid ground's motion, s from the rigid ground's R1z.
enum class UnmodelledKind { KneeCentre, JointCompliance, GroundCompliance };
constexpr int kNumUnmodelledKinds = 3;
struct UnmodelledEffect {
  UnmodelledKind kind = UnmodelledKind::KneeCentre;
  int joint = 0;  // physical joint (a knee for knee_centre; kNoJoint for ground_compliance)
  double value = 0.0;
};
// "knee_centre", "joint_compliance", "ground_compliance"
const char* unmodelledName(UnmodelledKind kind);
const char* unmodelledUnit(UnmodelledKind kind);
// Parses "NAME@JOINT=VALUE", "ground_compliance=VALUE" (std::invalid_argument with the reason
// on a bad spec).
UnmodelledEffect parseUnmodelledSpec(const std::string& spec);
// The closed range of values `synth` accepts for `e` on `robot`: knee_centre (0, the shorter
// femur's length per radian]; joint_compliance [the robot's peak envelope torque per radian,
// ∞) — stiffer than a joint the peak torque twists by one radian.
AdmissibleRange unmodelledRange(const UnmodelledEffect& e, const RobotParams& robot);

struct SynthOptions {
  int steps = 20;
  double rate = 500.0;           // sample rate [Hz]
  bool noise = true;             // false: exact values (no quantisation, no noise)
  std::uint64_t seed = 1;
  int encoder_counts = 1 << 14;  // per revolution, on α and the joint-side motor angles
  double torque_noise = 0.3;     // standard deviation [N·m]
  double force_noise = 2.0;      // standard deviation [N]
  double cop_noise = 0.002;      // standard deviation of the centres of pressure [m]
  double variation = 1.0;        // scale of the per-step random gait variation (0: none)
  std::vector<UnmodelledEffect> unmodelled;  // effects outside the library, see above
};

// Throws std::runtime_error when no variation of the gait gives a step the TRUE model walks
// (zero dynamics stalling or the gait's motion undefined).
MeasuredData synthesize(const RobotParams& robot, const GaitParameters& gait,
                        const GaitOptions& gait_options, const ModelOptions& model_options,
                        const std::vector<Effect>& effects, const SynthOptions& options);

// An effect of `kind` with a seeded random joint and a magnitude in its realistic range
// (coulomb 1–6 N·m, viscous 1–6 N·m·s/rad, rotor_inertia ×1.3–2, torque_offset ±1–5 N·m,
// torque_gain 0.85–0.95 or 1.05–1.2, encoder_offset ±0.01–0.05 rad (joints or alpha), backlash
// 0.01–0.04 rad, payload 2–8 kg, trunk_com ±0.02–0.05 m, slope 0.01–0.04 rad): hidden-effect
// tests of identification pipelines.
// `low` = true: magnitudes in the lowest quarter of those ranges (the short, noisy profile).
Effect randomEffect(EffectKind kind, std::mt19937_64& rng, bool low = false);

// An unmodelled effect with a seeded random joint and magnitude: knee_centre 0.01–0.02 m/rad,
// joint_compliance 2000–4000 N·m/rad, ground_compliance 4000–7000 N/m (the
// stance foot sinks 5–8 cm: sand, a gym mat) (`low`: the weakest quarter
// of each range).
UnmodelledEffect randomUnmodelled(UnmodelledKind kind, std::mt19937_64& rng, bool low = false);

}  // namespace gaitopt
