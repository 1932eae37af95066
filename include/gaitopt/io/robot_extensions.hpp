#pragma once
// The optional robot-file keys for the effects identified from measured data (`gaitopt
// diagnose`), read by parseRobot; every key is optional and neutral when absent:
//
//   joint_extras:                  # per physical joint; each joint key optional
//     coulomb: {knee_right: 3.2}   # N·m added to Γs
//     viscous: {hip_left: 1.5}     # N·m·s/rad added to Fv
//     rotor_inertia_factor: {knee_left: 1.4}
//   sensors:
//     torque_gain: {hip_right: 0.9}
//     torque_offset: {knee_left: -2.0}        # N·m
//     encoder_offset: {hip_left: 0.02, alpha: 0.01}   # rad (alpha: the trunk-angle sensor)
//     backlash: {knee_right: 0.03}            # rad, total dead-band width
//   hip_payload: 4.0               # kg at the hip
//   trunk_com_shift: 0.03          # m added to s3
//   ground_slope: 0.02             # rad, + uphill
//   foot_radius: 0.1               # m, rolling arc feet (rocker), 0 = point feet;
//                                  # 0 <= value < leg length min(l1 + l2, l4 + l5)
//   foot_offset: 0.05              # m, the arc's lowest point ahead of the ankle when the
//                                  # tibia is perpendicular to the ground; |value| < leg length
#include <string>

#include "gaitopt/io/yaml_reader.hpp"
#include "gaitopt/model/robot_params.hpp"
#include "gaitopt/model/stance.hpp"

namespace gaitopt {

// Reads the keys above from the robot document `doc` into `robot`.
void readRobotExtensions(const YamlMap& doc, RobotParams& robot);

// The YAML text of the non-neutral extension keys of `robot` (empty when all are neutral),
// top-level keys at column 0, values at full precision; readRobotExtensions reads it back.
std::string robotExtensionsYaml(const RobotParams& robot);

}  // namespace gaitopt
