#pragma once
// The part of an OpenSim model (.osim) that fixes its rigid-body geometry and mass: bodies
// with their mass properties, joints with their offset frames, coordinates and (CustomJoint)
// spatial transforms. Filled by io/osim_model_file.hpp from both the OpenSim 3 layout (a
// <Joint> inside each <Body>) and the OpenSim 4 layout (<JointSet>, <PhysicalOffsetFrame>).
// Lengths in metres, angles in radians, OpenSim's ground frame (x forward, y up, z right).
#include <Eigen/Dense>
#include <map>
#include <string>
#include <vector>

namespace gaitopt {

// A transform function of one coordinate (CustomJoint's TransformAxis).
struct OsimFunction {
  enum class Kind { Constant, Linear, SimmSpline, PiecewiseLinear, Polynomial, Multiplier };
  Kind kind = Kind::Constant;
  // Constant: {value}; Linear: {slope, intercept}; Polynomial: coefficients, highest power
  // first; splines and PiecewiseLinear: the knot ordinates, with `x` the abscissae.
  std::vector<double> x, y;
  double scale = 1.0;                // Multiplier
  std::vector<OsimFunction> inner;  // Multiplier: the one function it scales
};

struct OsimTransformAxis {
  bool rotation = true;             // rotation1..3 (radians) or translation1..3 (metres)
  std::vector<std::string> coordinates;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  OsimFunction function;
};

// A frame fixed in `body` (a body name or "ground"): position and x-y-z body-fixed Euler
// orientation in the body frame.
struct OsimFrame {
  std::string body;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Vector3d orientation = Eigen::Vector3d::Zero();
};

struct OsimCoordinate {
  std::string name;
  double default_value = 0.0;
};

struct OsimJoint {
  std::string name, type;  // type: the element name, e.g. "PinJoint", "CustomJoint"
  OsimFrame parent, child;
  std::vector<OsimCoordinate> coordinates;
  std::vector<OsimTransformAxis> axes;  // CustomJoint: its SpatialTransform
  int line = 0;                         // in the model file, for messages
};

struct OsimBody {
  std::string name;
  double mass = 0.0;
  Eigen::Vector3d mass_center = Eigen::Vector3d::Zero();  // in the body frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();      // about the mass centre, body axes
  int line = 0;
};

// A CoordinateCouplerConstraint: dependent = scale · function(independent) (e.g. a knee's
// translation coordinates following the knee angle).
struct OsimCoupler {
  std::string dependent, independent;
  OsimFunction function;
  double scale = 1.0;
  int line = 0;
};

struct OsimModel {
  std::string file;  // read from, for messages
  std::string name;
  int version = 0;  // OpenSimDocument Version, e.g. 30000, 40000
  Eigen::Vector3d gravity{0.0, -9.80665, 0.0};
  std::vector<OsimBody> bodies;  // without ground
  std::vector<OsimJoint> joints;
  std::vector<OsimCoupler> couplers;  // enforced ones only
};

// Value of `f` at coordinate value `q`.
double osimFunctionValue(const OsimFunction& f, double q);

// Pose in ground of every body (and "ground") with every independent coordinate at zero and
// every coupled coordinate at its coupler's value: the chain
// X_G,child = X_G,parent · X_parent,F · X_F,M(q) · X_child,M⁻¹ of each joint, X_F,M the
// identity at q = 0 except for a CustomJoint (its rotation functions as a body-fixed sequence
// about their axes, then its translation functions along theirs). Throws DataError for a body
// no joint reaches, a body that is the child of two joints, or a joint whose parent is never
// reached (a loop).
std::map<std::string, Eigen::Isometry3d> osimPosesAtZero(const OsimModel& model);

}  // namespace gaitopt
