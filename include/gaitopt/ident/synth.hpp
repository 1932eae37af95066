#pragma once
// Synthetic "measured" walking data from a TRUE model = a robot plus named effects
// (ident/effects.hpp): consecutive steps alternating the physical stance leg, each a small
// seeded random variation of a gait (excitation). Each step is the gait's double support
// (prescribed in time, leg 1 in front) then its single support. Single support follows the
// TRUE model's zero dynamics from the gait's initial α̇ (integrated here, so that a ground
// slope — gravity tilted in the gait's frame — is included); torques and reactions come from
// the TRUE model's inverse dynamics, in double support with the torque-optimal split
// R2x = argmin ‖Γ*‖² = Kᵀ J / Kᵀ K of (3.62). Then the sensor effects, encoder quantisation,
// torque and force noise.
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "gaitopt/gait/options.hpp"
#include "gaitopt/gait/parameters.hpp"
#include "gaitopt/ident/effects.hpp"
#include "gaitopt/ident/measured_data.hpp"

namespace gaitopt {

struct SynthOptions {
  int steps = 20;
  double rate = 500.0;           // sample rate [Hz]
  bool noise = true;             // false: exact values (no quantisation, no noise)
  std::uint64_t seed = 1;
  int encoder_counts = 1 << 14;  // per revolution, on α and the joint-side motor angles
  double torque_noise = 0.3;     // standard deviation [N·m]
  double force_noise = 2.0;      // standard deviation [N]
  double variation = 1.0;        // scale of the per-step random gait variation (0: none)
};

// Throws std::runtime_error when no variation of the gait gives a step the TRUE model walks
// (zero dynamics stalling or the gait's motion undefined).
MeasuredData synthesize(const RobotParams& robot, const GaitParameters& gait,
                        const GaitOptions& gait_options, const ModelOptions& model_options,
                        const std::vector<Effect>& effects, const SynthOptions& options);

// An effect of `kind` with a seeded random joint and a magnitude in the realistic range of
// issue 9 (coulomb 1–6 N·m, viscous 1–6 N·m·s/rad, rotor_inertia ×1.3–2, torque_offset ±1–5 N·m,
// torque_gain 0.85–0.95 or 1.05–1.2, encoder_offset ±0.01–0.05 rad (joints or alpha), backlash
// 0.01–0.04 rad, payload 2–8 kg, trunk_com ±0.02–0.05 m, slope 0.01–0.04 rad): hidden-effect
// tests of identification pipelines.
Effect randomEffect(EffectKind kind, std::mt19937_64& rng);

}  // namespace gaitopt
