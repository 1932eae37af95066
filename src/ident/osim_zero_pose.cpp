#include <vector>

#include "gaitopt/ident/data_error.hpp"
#include "gaitopt/ident/osim_model.hpp"

namespace gaitopt {
namespace {

// OpenSim's frame orientation: x-y-z body-fixed rotations.
Eigen::Isometry3d offset(const OsimFrame& f) {
  Eigen::Isometry3d x = Eigen::Isometry3d::Identity();
  x.translation() = f.translation;
  x.linear() = (Eigen::AngleAxisd(f.orientation.x(), Eigen::Vector3d::UnitX()) *
                Eigen::AngleAxisd(f.orientation.y(), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(f.orientation.z(), Eigen::Vector3d::UnitZ()))
                   .toRotationMatrix();
  return x;
}

using Coordinates = std::map<std::string, double>;

// Coupled coordinates at their couplers' values, the others at 0; a coupler on a coupled
// coordinate is resolved by repeating the passes (at most one per coupler).
Coordinates lumpingCoordinates(const OsimModel& model) {
  Coordinates q;
  const auto value = [&](const std::string& name) {
    const auto it = q.find(name);
    return it == q.end() ? 0.0 : it->second;
  };
  for (std::size_t pass = 0; pass < model.couplers.size(); ++pass)
    for (const OsimCoupler& c : model.couplers) q[c.dependent] = c.scale * osimFunctionValue(c.function, value(c.independent));
  return q;
}

// X_F,M at the coordinates `q`: only a CustomJoint's functions can move M off F at zero.
Eigen::Isometry3d mobilizer(const OsimJoint& j, const Coordinates& q) {
  Eigen::Isometry3d x = Eigen::Isometry3d::Identity();
  for (const OsimTransformAxis& a : j.axes) {
    const auto it = a.coordinates.empty() ? q.end() : q.find(a.coordinates.front());
    const double v = osimFunctionValue(a.function, it == q.end() ? 0.0 : it->second);
    if (a.rotation) x.linear() = x.linear() * Eigen::AngleAxisd(v, a.axis).toRotationMatrix();
    else x.translation() += v * a.axis;
  }
  return x;
}

}  // namespace

std::map<std::string, Eigen::Isometry3d> osimPosesAtZero(const OsimModel& model) {
  std::map<std::string, Eigen::Isometry3d> pose{{"ground", Eigen::Isometry3d::Identity()}};
  std::multimap<std::string, const OsimJoint*> joints_from;  // parent body -> its joints
  std::map<std::string, const OsimJoint*> joint_to;
  for (const OsimJoint& j : model.joints) {
    if (j.child.body == "ground") throw DataError(model.file, j.name, j.line, "a joint whose child is ground is not read");
    if (!joint_to.emplace(j.child.body, &j).second)
      throw DataError(model.file, j.name, j.line,
                      "body '" + j.child.body + "' is the child of two joints (closed loops are not read)");
    joints_from.emplace(j.parent.body, &j);
  }
  const Coordinates q = lumpingCoordinates(model);
  // Breadth first from ground: a body is placed once its parent is.
  std::vector<std::string> queue{"ground"};
  for (std::size_t next = 0; next < queue.size(); ++next) {
    const Eigen::Isometry3d parent = pose.at(queue[next]);
    const auto [first, last] = joints_from.equal_range(queue[next]);
    for (auto it = first; it != last; ++it) {
      const OsimJoint& j = *it->second;
      if (pose.count(j.child.body)) continue;
      pose[j.child.body] = parent * offset(j.parent) * mobilizer(j, q) * offset(j.child).inverse();
      queue.push_back(j.child.body);
    }
  }
  for (const OsimBody& b : model.bodies)
    if (!pose.count(b.name))
      throw DataError(model.file, b.name, b.line, "body not connected to ground by joints");
  return pose;
}

}  // namespace gaitopt
