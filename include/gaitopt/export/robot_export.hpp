#pragma once
// The robot as MuJoCo MJCF and as URDF, for simulators. Both describe the same tree: the
// trunk as floating base (planar: x, z and pitch), a femur at the hip for each leg and a tibia
// at its knee, the support bar as a point mass at the hip, point feet as small spheres.
// Joint values are the joint-side motor angles φ = D_Γᵀ q with the left leg as leg 1
// (knee_left = δ1, hip_left = −δ2, hip_right = −(δ2 + δ3), knee_right = δ4), so the
// `phi_J` and `tau_J` columns of `gaitopt export` apply to them unchanged; rotor inertia is
// MuJoCo's `armature` I_m N², the high-gear approximation (A.1).
#include <string>

#include "gaitopt/model/model.hpp"

namespace gaitopt {

struct ModelExportOptions {
  double foot_radius = 0.01;    // [m] contact sphere; the MJCF floor is at z = −radius so the
                                // foot centre (the model's point foot) is at z = 0 on contact
  double ground_friction = 0.8; // MJCF floor/foot sliding friction
  double timestep = 0.0005;     // [s] MJCF <option timestep>
};

std::string robotMjcf(const RobotParams& robot, const ModelExportOptions& options = {});
std::string robotUrdf(const RobotParams& robot, const ModelExportOptions& options = {});

// qpos = L X maps gaitopt's floating coordinates X = [α, δ1..δ4, x_t, z_t] (left leg = leg 1,
// (x_t, z_t) the trunk-with-bar CoM) to the MJCF joint values in tree order
// (rootx, rootz, rooty, hip_left, knee_left, hip_right, knee_right); rooty = θ3 − π/2.
Eigen::Matrix<double, 7, 7> mjcfCoordinateMap();

}  // namespace gaitopt
