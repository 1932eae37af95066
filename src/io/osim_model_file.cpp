#include "gaitopt/io/osim_model_file.hpp"

#include <cmath>
#include <sstream>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/csv_table.hpp"

namespace gaitopt {
namespace {

constexpr const char* kGround = "ground";

class OsimReader {
 public:
  explicit OsimReader(const std::string& file) : file_(file) {}

  OsimModel model(const XmlElement& root) {
    if (root.name != "OpenSimDocument") fail(root, "", "the root element is '" + root.name + "', not OpenSimDocument");
    const XmlElement& m = required(root, "Model", "");
    OsimModel out;
    if (const std::string* v = root.attribute("Version")) {
      const double version = number(root, "Version", *v);
      if (version < 0.0 || version > 1e6 || version != std::floor(version))
        fail(root, "Version", "not a document version: '" + printable(*v) + "'");
      out.version = static_cast<int>(version);
    }
    if (const std::string* n = m.attribute("name")) out.name = *n;
    if (const XmlElement* g = m.child("gravity")) out.gravity = vector3(*g, "gravity");
    const XmlElement& bodies = objects(required(m, "BodySet", ""), "BodySet");
    for (const XmlElement& b : bodies.children)
      if (b.name == "Body" && nameOf(b) != kGround) out.bodies.push_back(body(b, out.version));
    if (const XmlElement* set = m.child("JointSet")) {
      if (const XmlElement* list = set->child("objects"))
        for (const XmlElement& j : list->children) out.joints.push_back(jointV4(j));
    }
    for (const XmlElement& b : bodies.children)  // OpenSim 3: the joint inside its child body
      if (const XmlElement* holder = b.name == "Body" ? b.child("Joint") : nullptr)
        for (const XmlElement& j : holder->children) out.joints.push_back(jointV3(j, nameOf(b)));
    if (const XmlElement* set = m.child("ConstraintSet")) {
      if (const XmlElement* list = set->child("objects"))
        for (const XmlElement& c : list->children)
          if (c.name == "CoordinateCouplerConstraint" && enforced(c)) out.couplers.push_back(coupler(c));
    }
    for (OsimJoint& j : out.joints) {
      requireBody(out, j, j.parent.body);
      requireBody(out, j, j.child.body);
    }
    return out;
  }

 private:
  [[noreturn]] void fail(const XmlElement& e, const std::string& key, const std::string& problem) const {
    throw ConfigError(file_, key, e.line, problem);
  }

  const XmlElement& required(const XmlElement& e, const std::string& child, const std::string& owner) const {
    const XmlElement* c = e.child(child);
    if (!c) fail(e, owner.empty() ? child : owner + "." + child, "missing <" + child + "> in <" + e.name + ">");
    return *c;
  }

  const XmlElement& objects(const XmlElement& set, const std::string& key) const {
    return required(set, "objects", key);
  }

  std::string nameOf(const XmlElement& e) const {
    const std::string* n = e.attribute("name");
    if (!n || n->empty()) fail(e, e.name, "<" + e.name + "> without a name attribute");
    return *n;
  }

  double number(const XmlElement& e, const std::string& key, const std::string& field) const {
    const std::optional<double> v = parseDecimal(field);
    if (!v) fail(e, key, decimalProblem(field));
    return *v;
  }

  std::vector<double> numbers(const XmlElement& e, const std::string& key) const {
    std::istringstream in(e.text);
    std::vector<double> out;
    for (std::string field; in >> field;) out.push_back(number(e, key, field));
    return out;
  }

  std::vector<double> numbers(const XmlElement& e, const std::string& key, std::size_t count) const {
    std::vector<double> v = numbers(e, key);
    if (v.size() != count)
      fail(e, key, std::to_string(v.size()) + " numbers where " + std::to_string(count) + " are expected");
    return v;
  }

  Eigen::Vector3d vector3(const XmlElement& e, const std::string& key) const {
    const std::vector<double> v = numbers(e, key, 3);
    return {v[0], v[1], v[2]};
  }

  Eigen::Vector3d optionalVector3(const XmlElement& owner, const std::string& child, const std::string& key) const {
    const XmlElement* c = owner.child(child);
    return c ? vector3(*c, key + "." + child) : Eigen::Vector3d::Zero();
  }

  OsimBody body(const XmlElement& b, int version) const {
    OsimBody out;
    out.name = nameOf(b);
    out.line = b.line;
    const std::string key = out.name;
    out.mass = numbers(required(b, "mass", key), key + ".mass", 1)[0];
    if (out.mass < 0.0) fail(*b.child("mass"), key + ".mass", "negative mass");
    out.mass_center = optionalVector3(b, "mass_center", key);
    std::vector<double> i6(6, 0.0);  // Ixx Iyy Izz Ixy Ixz Iyz
    if (const XmlElement* inertia = b.child("inertia")) {
      i6 = numbers(*inertia, key + ".inertia", 6);
    } else if (version < 40000) {
      const char* names[] = {"inertia_xx", "inertia_yy", "inertia_zz", "inertia_xy", "inertia_xz", "inertia_yz"};
      for (int k = 0; k < 6; ++k)
        if (const XmlElement* c = b.child(names[k])) i6[k] = numbers(*c, key + "." + names[k], 1)[0];
    }
    out.inertia << i6[0], i6[3], i6[4], i6[3], i6[1], i6[5], i6[4], i6[5], i6[2];
    if (i6[0] < 0.0 || i6[1] < 0.0 || i6[2] < 0.0) fail(b, key + ".inertia", "negative moment of inertia");
    return out;
  }

  // A frame path of OpenSim 4 ("/bodyset/femur_r", "/ground", "../pelvis", "femur_r_offset")
  // resolved against the joint's own offset frames, then as a body.
  OsimFrame frameV4(const XmlElement& joint, const std::string& path, const std::string& key) const {
    std::string name = path;
    while (name.compare(0, 3, "../") == 0) name.erase(0, 3);
    if (const XmlElement* frames = joint.child("frames")) {
      for (const XmlElement& f : frames->children) {
        if (f.name != "PhysicalOffsetFrame" || nameOf(f) != name) continue;
        const std::string fkey = key + "." + name;
        const XmlElement* socket = f.child("socket_parent");
        if (!socket) socket = f.child("socket_parent_connectee_name");
        if (!socket) fail(f, fkey, "offset frame without socket_parent");
        OsimFrame out;
        out.body = bodyPath(f, trimmed(socket->text), fkey);
        out.translation = optionalVector3(f, "translation", fkey);
        out.orientation = optionalVector3(f, "orientation", fkey);
        return out;
      }
    }
    OsimFrame out;
    out.body = bodyPath(joint, path, key);
    return out;
  }

  // A path naming a body or ground ("/bodyset/femur_r", "/ground", "../pelvis", "pelvis");
  // an offset frame on another offset frame is not read.
  std::string bodyPath(const XmlElement& e, const std::string& path, const std::string& key) const {
    std::string name = path;
    while (name.compare(0, 3, "../") == 0) name.erase(0, 3);
    if (name.compare(0, 9, "/bodyset/") == 0) name.erase(0, 9);
    if (name == "/ground") name = kGround;
    if (name.empty() || name.find('/') != std::string::npos)
      fail(e, key, "frame '" + path + "' is neither an offset frame of the joint nor a body");
    return name;
  }

  static std::string trimmed(const std::string& s) {
    const std::size_t a = s.find_first_not_of(" \t\r\n");
    if (a == std::string::npos) return "";
    return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
  }

  const XmlElement& socket(const XmlElement& j, const std::string& which, const std::string& key) const {
    for (const std::string& tag : {"socket_" + which, "socket_" + which + "_connectee_name", which})
      if (const XmlElement* s = j.child(tag)) return *s;
    fail(j, key, "missing <socket_" + which + "> in <" + j.name + ">");
  }

  OsimJoint jointV4(const XmlElement& j) const {
    OsimJoint out = jointCommon(j, "coordinates");
    out.parent = frameV4(j, trimmed(socket(j, "parent_frame", out.name).text), out.name + ".parent_frame");
    out.child = frameV4(j, trimmed(socket(j, "child_frame", out.name).text), out.name + ".child_frame");
    return out;
  }

  OsimJoint jointV3(const XmlElement& j, const std::string& child_body) const {
    OsimJoint out = jointCommon(j, "CoordinateSet");
    out.parent.body = trimmed(required(j, "parent_body", out.name).text);
    out.parent.translation = optionalVector3(j, "location_in_parent", out.name);
    out.parent.orientation = optionalVector3(j, "orientation_in_parent", out.name);
    out.child.body = child_body;
    out.child.translation = optionalVector3(j, "location", out.name);
    out.child.orientation = optionalVector3(j, "orientation", out.name);
    return out;
  }

  OsimJoint jointCommon(const XmlElement& j, const char* coordinate_list) const {
    OsimJoint out;
    out.name = nameOf(j);
    out.type = j.name;
    out.line = j.line;
    if (const XmlElement* list = j.child(coordinate_list)) {
      const XmlElement* items = list->child("objects") ? list->child("objects") : list;
      for (const XmlElement& c : items->children) {
        if (c.name != "Coordinate") continue;
        OsimCoordinate coordinate{nameOf(c), 0.0};
        if (const XmlElement* d = c.child("default_value"))
          coordinate.default_value = numbers(*d, out.name + "." + coordinate.name + ".default_value", 1)[0];
        out.coordinates.push_back(coordinate);
      }
    }
    if (const XmlElement* transform = j.child("SpatialTransform"))
      for (const XmlElement& a : transform->children)
        if (a.name == "TransformAxis") out.axes.push_back(transformAxis(a, out.name));
    return out;
  }

  OsimTransformAxis transformAxis(const XmlElement& a, const std::string& joint) const {
    OsimTransformAxis out;
    const std::string axis_name = nameOf(a);
    const std::string key = joint + "." + axis_name;
    if (axis_name.compare(0, 8, "rotation") == 0) out.rotation = true;
    else if (axis_name.compare(0, 11, "translation") == 0) out.rotation = false;
    else fail(a, key, "TransformAxis named neither rotation<k> nor translation<k>");
    if (const XmlElement* c = a.child("coordinates")) {
      std::istringstream in(c->text);
      for (std::string name; in >> name;) out.coordinates.push_back(name);
    }
    out.axis = vector3(required(a, "axis", key), key + ".axis");
    if (out.axis.norm() < 1e-12) fail(a, key + ".axis", "zero axis");
    out.axis.normalize();
    out.function = functionIn(a, key);
    return out;
  }

  // OpenSim 4 writes isEnforced, OpenSim 3 isDisabled.
  bool enforced(const XmlElement& c) const {
    const XmlElement* on = c.child("isEnforced");
    const XmlElement* off = c.child("isDisabled");
    return !(on && trimmed(on->text) == "false") && !(off && trimmed(off->text) == "true");
  }

  OsimCoupler coupler(const XmlElement& c) const {
    OsimCoupler out;
    const std::string key = nameOf(c);
    out.line = c.line;
    out.dependent = trimmed(required(c, "dependent_coordinate_name", key).text);
    std::istringstream in(required(c, "independent_coordinate_names", key).text);
    std::vector<std::string> names;
    for (std::string n; in >> n;) names.push_back(n);
    if (names.size() != 1 || out.dependent.empty())
      fail(c, key, "a coupler of one dependent and one independent coordinate is expected");
    out.independent = names.front();
    out.function = functionIn(c, key, "coupled_coordinates_function");
    if (const XmlElement* s = c.child("scale_factor")) out.scale = numbers(*s, key + ".scale_factor", 1)[0];
    return out;
  }

  // The function of a TransformAxis, multiplier or coupler: an element named `tag` wrapping
  // it (OpenSim 3, multipliers, couplers) or the function element named `tag` (OpenSim 4).
  OsimFunction functionIn(const XmlElement& owner, const std::string& key, const std::string& tag = "function") const {
    if (const XmlElement* wrapper = owner.child(tag)) {
      if (wrapper->children.size() != 1) fail(*wrapper, key + "." + tag, "<" + tag + "> must hold exactly one function");
      return function(wrapper->children.front(), key + "." + tag);
    }
    for (const XmlElement& c : owner.children) {
      const std::string* n = c.attribute("name");
      if (n && *n == tag) return function(c, key + "." + tag);
    }
    fail(owner, key, "no <" + tag + ">");
  }

  OsimFunction function(const XmlElement& f, const std::string& key) const {
    OsimFunction out;
    const auto knots = [&] {
      out.x = numbers(required(f, "x", key), key + ".x");
      out.y = numbers(required(f, "y", key), key + ".y");
      if (out.x.size() != out.y.size() || out.x.size() < 2)
        fail(f, key, "needs as many x as y values, at least 2");
      for (std::size_t i = 1; i < out.x.size(); ++i)
        if (!(out.x[i] > out.x[i - 1])) fail(f, key + ".x", "x values must increase strictly");
    };
    if (f.name == "Constant") {
      out.y = numbers(required(f, "value", key), key + ".value", 1);
    } else if (f.name == "LinearFunction") {
      out.kind = OsimFunction::Kind::Linear;
      out.y = numbers(required(f, "coefficients", key), key + ".coefficients", 2);
    } else if (f.name == "SimmSpline") {
      out.kind = OsimFunction::Kind::SimmSpline;
      knots();
    } else if (f.name == "PiecewiseLinearFunction") {
      out.kind = OsimFunction::Kind::PiecewiseLinear;
      knots();
    } else if (f.name == "PolynomialFunction") {
      out.kind = OsimFunction::Kind::Polynomial;
      out.y = numbers(required(f, "coefficients", key), key + ".coefficients");
      if (out.y.empty()) fail(f, key, "no polynomial coefficients");
    } else if (f.name == "MultiplierFunction") {
      out.kind = OsimFunction::Kind::Multiplier;
      out.inner.push_back(functionIn(f, key));
      if (const XmlElement* s = f.child("scale")) out.scale = numbers(*s, key + ".scale", 1)[0];
    } else {
      fail(f, key, "transform function <" + f.name + "> is not read (Constant, LinearFunction, SimmSpline, "
                   "PiecewiseLinearFunction, PolynomialFunction and MultiplierFunction are)");
    }
    return out;
  }

  void requireBody(const OsimModel& m, const OsimJoint& j, const std::string& body) const {
    if (body == kGround) return;
    for (const OsimBody& b : m.bodies)
      if (b.name == body) return;
    throw ConfigError(file_, j.name, j.line, "joint frame on '" + body + "', which is not a body of the model");
  }

  const std::string& file_;
};

}  // namespace

OsimModel parseOsimModel(const XmlElement& root, const std::string& file) {
  OsimModel model = OsimReader(file).model(root);
  model.file = file;
  return model;
}

OsimModel loadOsimModel(const std::string& path) {
  OsimModel model = parseOsimModel(readXmlFile(path), path);
  model.file = path;
  return model;
}

}  // namespace gaitopt
