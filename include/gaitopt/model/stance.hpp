#pragma once
// The physical legs behind the thesis' leg 1 / leg 2 convention. The model always walks on
// leg 1; a real robot or a person alternates, so measured data says per sample which physical
// leg is leg 1, and per-joint robot properties are given per physical joint.
#include <array>

namespace gaitopt {

// Which physical leg is leg 1 (the stance leg in SS, the front leg in DS).
enum class Stance { Left, Right };

// Physical joint names, in the order of JointExtras and SensorModel arrays (robot_params.hpp).
inline constexpr std::array<const char*, 4> kPhysicalJointNames = {"knee_left", "hip_left",
                                                                   "hip_right", "knee_right"};

}  // namespace gaitopt
