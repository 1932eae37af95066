#include "gaitopt/ident/osim_lumping.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "gaitopt/ident/data_error.hpp"

namespace gaitopt {
namespace {

// Human joint ranges, wide, for plots and import checks (as configs/robot/human_subject01.yaml):
// knees from straight to 90° of flexion beyond straight (δ = −180° + flexion), hips ±75° about
// the trunk.
constexpr double kDeg = M_PI / 180.0;
constexpr double kHipMin = -255.0 * kDeg, kHipMax = -105.0 * kDeg;
constexpr double kKneeMin = -230.0 * kDeg, kKneeMax = -90.0 * kDeg;

using Poses = std::map<std::string, Eigen::Isometry3d>;

class Lumper {
 public:
  explicit Lumper(const OsimModel& m) : m_(m), pose_(osimPosesAtZero(m)) {
    for (const OsimBody& b : m.bodies) body_[b.name] = &b;
    for (const OsimJoint& j : m.joints) {
      joint_to_[j.child.body] = &j;
      joints_from_.emplace(j.parent.body, &j);
    }
  }

  [[noreturn]] void fail(const std::string& key, int line, const std::string& problem) const {
    throw DataError(m_.file, key, line, problem);
  }

  const OsimBody& body(const std::string& name) const {
    const auto it = body_.find(name);
    if (it == body_.end()) fail(name, 0, "no body '" + name + "' in the model (the thighs are named by --thighs)");
    return *it->second;
  }

  // `root` and every body below it.
  std::set<std::string> subtree(const std::string& root) const {
    std::set<std::string> out{root};
    std::vector<std::string> todo{root};
    while (!todo.empty()) {
      const std::string b = todo.back();
      todo.pop_back();
      const auto [first, last] = joints_from_.equal_range(b);
      for (auto it = first; it != last; ++it)
        if (out.insert(it->second->child.body).second) todo.push_back(it->second->child.body);
    }
    return out;
  }

  double massOf(const std::set<std::string>& bodies) const {
    double mass = 0.0;
    for (const std::string& b : bodies) mass += body(b).mass;
    return mass;
  }

  // The heaviest subtree hanging from `parent` through a joint: the shank of a thigh, the
  // foot of a shank. Returns its joint.
  const OsimJoint& heaviestChild(const std::string& parent, const std::string& what) const {
    const OsimJoint* best = nullptr;
    double best_mass = -1.0;
    const auto [first, last] = joints_from_.equal_range(parent);
    for (auto it = first; it != last; ++it) {
      const double mass = massOf(subtree(it->second->child.body));
      if (mass > best_mass) best = it->second, best_mass = mass;
    }
    if (!best) fail(parent, body(parent).line, "no joint below '" + parent + "': the " + what + " is undefined");
    return *best;
  }

  // Centre of `j` in ground: the origin of its child-side frame M.
  Eigen::Vector3d centre(const OsimJoint& j) const { return pose_.at(j.child.body) * j.child.translation; }

  // Mass, CoM and planar inertia Izz about the CoM of `bodies`, in ground.
  void massProperties(const std::set<std::string>& bodies, OsimLink& link, Eigen::Vector3d& com) const {
    link.bodies.assign(bodies.begin(), bodies.end());
    link.mass = massOf(bodies);
    if (!(link.mass > 0.0)) fail(*bodies.begin(), 0, "the lump of " + list(bodies) + " has no mass");
    com.setZero();
    for (const std::string& b : bodies) com += body(b).mass * (pose_.at(b) * body(b).mass_center);
    com /= link.mass;
    link.inertia = 0.0;
    for (const std::string& b : bodies) {
      const OsimBody& ob = body(b);
      const Eigen::Matrix3d r = pose_.at(b).linear();
      const Eigen::Vector3d c = pose_.at(b) * ob.mass_center - com;
      link.inertia += (r * ob.inertia * r.transpose())(2, 2) + ob.mass * c.head<2>().squaredNorm();  // Steiner
    }
    if (!(link.inertia > 0.0)) fail(*bodies.begin(), 0, "the lump of " + list(bodies) + " has no inertia about z");
    if (!std::isfinite(link.mass) || !std::isfinite(link.inertia) || !com.allFinite())
      fail(*bodies.begin(), 0, "the lump of " + list(bodies) + " has a mass, CoM or inertia beyond double range");
  }

  // A leg link from joint centre p (proximal) to d (distal), sagittal components.
  void link(const std::set<std::string>& bodies, const Eigen::Vector3d& p, const Eigen::Vector3d& d,
            OsimLink& out) const {
    Eigen::Vector3d com;
    massProperties(bodies, out, com);
    const Eigen::Vector2d axis = (d - p).head<2>();
    out.length = axis.norm();
    if (!(out.length > 0.0) || !std::isfinite(out.length))
      fail(*bodies.begin(), 0, "the joint centres of the lump of " + list(bodies) + " coincide in the sagittal plane or lie beyond double range");
    const Eigen::Vector2d u = axis / out.length, n(-u.y(), u.x());  // n: forward of a leg pointing down
    out.com = (com - p).head<2>().dot(u);
    out.com_normal = (com - p).head<2>().dot(n);
  }

  static std::string list(const std::set<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : " + ") + n;
    return out;
  }

  OsimLumping lump(const std::array<std::string, 2>& thighs) const {
    OsimLumping out;
    const double g = m_.gravity.norm();
    if (!(g > 0.0) || std::abs(m_.gravity.y() + g) > 1e-9 * g)
      fail("gravity", 0, "gravity is not along -y: the sagittal lumping takes OpenSim's y as up");
    out.gravity = g;
    for (const OsimBody& b : m_.bodies) out.model_mass += b.mass;
    std::set<std::string> legs;
    std::array<Eigen::Vector3d, 2> hips;
    const OsimJoint* first_hip = nullptr;
    for (int side = 0; side < 2; ++side) {
      const OsimBody& thigh = body(thighs[side]);
      const auto hip_joint = joint_to_.find(thigh.name);
      if (hip_joint == joint_to_.end()) fail(thigh.name, thigh.line, "the thigh hangs from no joint");
      const OsimJoint& knee = heaviestChild(thigh.name, "knee");
      const OsimJoint& ankle = heaviestChild(knee.child.body, "ankle");
      const std::set<std::string> leg = subtree(thigh.name), shank = subtree(knee.child.body);
      std::set<std::string> femur;
      std::set_difference(leg.begin(), leg.end(), shank.begin(), shank.end(), std::inserter(femur, femur.end()));
      for (const std::string& b : leg)
        if (!legs.insert(b).second)
          fail(thigh.name, thigh.line, "body '" + b + "' in both legs: the two thighs must be distinct legs");
      hips[side] = centre(*hip_joint->second);
      if (side == 0) first_hip = hip_joint->second;
      const Eigen::Vector3d k = centre(knee), a = centre(ankle);
      link(femur, hips[side], k, out.femur[side]);
      link(shank, k, a, out.tibia[side]);
      out.out_of_plane = std::max({out.out_of_plane, std::abs(k.z() - hips[side].z()), std::abs(a.z() - k.z())});
    }
    std::set<std::string> trunk;
    for (const OsimBody& b : m_.bodies)
      if (!legs.count(b.name)) trunk.insert(b.name);
    if (trunk.empty()) fail("BodySet", 0, "no body besides the legs: the trunk is undefined");
    Eigen::Vector3d com;
    massProperties(trunk, out.trunk, com);
    const Eigen::Vector3d hip = 0.5 * (hips[0] + hips[1]);
    out.trunk_com_forward = com.x() - hip.x();
    out.trunk_com_up = com.y() - hip.y();
    out.trunk.com = (com - hip).head<2>().norm();
    out.pelvis_frame = pelvisFrame(*first_hip, trunk);
    asymmetry(out);
    out.robot = robot(out);
    return out;
  }

  // The pelvis is the body the first thigh hangs from; the back joint its joint to the heaviest
  // other trunk subtree; the torso lump every trunk body but the pelvis, so that the two masses
  // make m3.
  std::optional<PelvisFrame> pelvisFrame(const OsimJoint& hip, std::set<std::string> trunk) const {
    const std::string pelvis = hip.parent.body;
    if (!body_.count(pelvis) || trunk.size() < 2) return std::nullopt;
    const OsimJoint* back = nullptr;
    double back_mass = 0.0;
    const auto [first, last] = joints_from_.equal_range(pelvis);
    for (auto it = first; it != last; ++it) {
      const std::string& child = it->second->child.body;
      const double mass = trunk.count(child) ? massOf(subtree(child)) : 0.0;
      if (mass > back_mass) back = it->second, back_mass = mass;
    }
    if (!back) return std::nullopt;
    trunk.erase(pelvis);
    OsimLink torso;
    Eigen::Vector3d com;
    massProperties(trunk, torso, com);
    const auto xy = [](const Eigen::Vector3d& v) { return std::array<double, 2>{v.x(), v.y()}; };
    const Eigen::Isometry3d to_pelvis = pose_.at(pelvis).inverse();
    PelvisFrame f;
    f.hip = xy(to_pelvis * centre(hip));
    f.pelvis_com = xy(body(pelvis).mass_center);
    f.pelvis_mass = body(pelvis).mass;
    f.back = xy(to_pelvis * centre(*back));
    f.torso_com = xy(pose_.at(back->child.body).inverse() * com - back->child.translation);
    f.torso_mass = torso.mass;
    return f;
  }

  static void asymmetry(OsimLumping& out) {
    const auto check = [&](const char* what, double r, double l) {
      const double rel = std::abs(r - l) / (0.5 * (std::abs(r) + std::abs(l)));
      if (rel > out.asymmetry || out.asymmetry_quantity.empty()) out.asymmetry = rel, out.asymmetry_quantity = what;
    };
    for (const auto& [name, links] : {std::pair<const char*, const std::array<OsimLink, 2>*>{"tibia", &out.tibia},
                                      {"femur", &out.femur}}) {
      const std::string n = name;
      check((n + " mass").c_str(), (*links)[0].mass, (*links)[1].mass);
      check((n + " length").c_str(), (*links)[0].length, (*links)[1].length);
      check((n + " CoM").c_str(), (*links)[0].com, (*links)[1].com);
      check((n + " inertia").c_str(), (*links)[0].inertia, (*links)[1].inertia);
    }
  }

  static RobotParams robot(const OsimLumping& out) {
    const auto mean = [](const std::array<OsimLink, 2>& l, double OsimLink::*field) {
      return 0.5 * (l[0].*field + l[1].*field);
    };
    RobotParams r;
    r.l1 = r.l5 = mean(out.tibia, &OsimLink::length);
    r.l2 = r.l4 = mean(out.femur, &OsimLink::length);
    r.s = {mean(out.tibia, &OsimLink::com), mean(out.femur, &OsimLink::com), out.trunk.com,
           mean(out.femur, &OsimLink::com), mean(out.tibia, &OsimLink::com)};
    r.mass = {mean(out.tibia, &OsimLink::mass), mean(out.femur, &OsimLink::mass), out.trunk.mass,
              mean(out.femur, &OsimLink::mass), mean(out.tibia, &OsimLink::mass)};
    r.inertia = {mean(out.tibia, &OsimLink::inertia), mean(out.femur, &OsimLink::inertia), out.trunk.inertia,
                 mean(out.femur, &OsimLink::inertia), mean(out.tibia, &OsimLink::inertia)};
    r.gravity = out.gravity;
    r.limits = {kHipMin, kHipMax, kKneeMin, kKneeMax};
    return r;
  }

 private:
  const OsimModel& m_;
  const Poses pose_;
  std::map<std::string, const OsimBody*> body_;
  std::map<std::string, const OsimJoint*> joint_to_;
  std::multimap<std::string, const OsimJoint*> joints_from_;
};

}  // namespace

OsimLumping lumpOsimModel(const OsimModel& model, const std::array<std::string, 2>& thighs) {
  return Lumper(model).lump(thighs);
}

}  // namespace gaitopt
