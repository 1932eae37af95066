#pragma once
// Constant description of a RABBIT-class five-link biped, exactly as read from a robot YAML
// file (before the support bar is folded into the trunk). SI units, radians.
#include <array>
#include <string>

namespace gaitopt {

// Lateral support bar (§1.4.2.4). Either an equivalent point mass at the hip, or the bar
// geometry from which that mass follows by (1.29) with l_G = L_b/2.
struct SupportBar {
  bool present = false;
  double equivalent_mass = 0.0;  // m_eq [kg], used by (1.24)
  bool from_geometry = false;    // true when L_b, l_c, M_b, M_c were given
  double bar_length = 0.0;       // L_b [m]
  double overhang = 0.0;         // l_c [m]
  double bar_mass = 0.0;         // M_b [kg]
  double counterweight_mass = 0.0;  // M_c [kg]
};

// Piecewise-linear joint-side torque-speed envelope (3.47): |Γ*| ≤ Γmax(|ω|).
// Breakpoints (speed [rad/s], torque [N·m]) in increasing speed; beyond the last, 0.
struct TorqueEnvelope {
  std::array<double, 4> speed{0.0, 5.45, 10.47, 12.15};
  std::array<double, 4> torque{140.0, 140.0, 60.0, 0.0};
};

// Software joint limits (3.39), on δ2, δ2+δ3 (hips) and δ1, δ4 (knees) [rad].
struct JointLimits {
  double hip_min = -4.537856055185257;   // -260°
  double hip_max = -1.9198621771937625;  // -110°
  double knee_min = -4.014257279586958;  // -230°
  double knee_max = -2.2165681500327987; // -127°
};

// Effects the thesis model lacks, identified from measured data by `gaitopt diagnose` and
// injected by `gaitopt synth` (ident/). All neutral by default, so a robot file without them
// gives exactly the thesis model. Arrays are per PHYSICAL joint (knee_left, hip_left,
// hip_right, knee_right): the motor number of a physical joint changes with the stance leg
// (ident/effects.hpp maps them).
struct JointExtras {
  std::array<double, 4> coulomb{};  // added to Γs [N·m]
  std::array<double, 4> viscous{};  // added to Fv [N·m·s/rad]
  std::array<double, 4> rotor_inertia_factor{1.0, 1.0, 1.0, 1.0};  // on I_m
};

// What the sensors read: measured Γ* = torque_gain × Γ* + torque_offset; measured joint-side
// motor angle = link angle + encoder_offset + backlash/2 × tanh(Γ*/1 N·m); measured α = α +
// alpha_offset.
struct SensorModel {
  std::array<double, 4> torque_gain{1.0, 1.0, 1.0, 1.0};
  std::array<double, 4> torque_offset{};   // [N·m]
  std::array<double, 4> encoder_offset{};  // [rad]
  std::array<double, 4> backlash{};        // total dead-band width [rad]
  double alpha_offset = 0.0;               // [rad]
};

struct RobotParams {
  std::string name;
  std::string source_file;  // path it was read from (for messages)
  // Lengths: tibias l1, l5 and femurs l2, l4 [m].
  double l1 = 0.4, l2 = 0.4, l4 = 0.4, l5 = 0.4;
  // CoM offsets [m]: s1, s5 from the knee; s2, s4, s3 from the hip (digest §1.3).
  std::array<double, 5> s{};
  std::array<double, 5> mass{};     // m1..m5 [kg], trunk without the bar
  std::array<double, 5> inertia{};  // I_y1..I_y5 about each CoM [kg·m²]
  std::array<double, 4> rotor_inertia{};  // I_m1..I_m4, motor side [kg·m²]
  double gear_ratio = 50.0;               // N
  std::array<double, 4> coulomb{};        // Γs1..Γs4, joint side [N·m]
  std::array<double, 4> viscous{};        // fv1..fv4, joint side [N·m·s/rad]
  double motor_torque_constant = 0.16;    // K_em, motor side [N·m/A]
  double motor_resistance = 0.96;         // R [Ω]
  TorqueEnvelope envelope;
  JointLimits limits;
  double gravity = 9.81;
  SupportBar bar;
  double trunk_length = 0.625;  // hip to top of trunk [m]; drawing only, not in the dynamics
  JointExtras joint_extras;     // used per stance by ident/; gait optimisation ignores them
  SensorModel sensors;          // used by ident/ only
  double hip_payload = 0.0;     // extra point mass at the hip [kg], folded like the bar (1.24)
  double trunk_com_shift = 0.0; // added to s3 (trunk alone, before the bar) [m]
  double ground_slope = 0.0;    // ground inclination [rad], + uphill; used by ident/ only
  double foot_radius = 0.0;     // rolling arc feet (model/rocker_foot.hpp) [m], 0 = point
  double foot_offset = 0.0;     // the arc's lowest point ahead of the ankle [m]; ident/ only
};

}  // namespace gaitopt
