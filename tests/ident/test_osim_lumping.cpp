// Five-link lumping of OpenSim models (ident/osim_lumping.hpp, io/osim_model_file.hpp) on a
// tiny hand-written model, in the OpenSim 4 and the OpenSim 3 layout, whose lumped values are
// worked out by hand below: pelvis 10 kg at the origin, torso 20 kg 0.3 m above its joint
// (0.1 m behind and 0.1 m above the pelvis origin), hips 0.1 m below the pelvis origin, femurs
// 8 kg (left 8.2 kg) with the CoM 0.2 m below the hip, a 0.1 kg patella on each femur 0.05 m
// ahead of the knee, knees 0.4 m below the hips (a scaled spline: in the OpenSim 4 model a
// knee translation coordinate coupled to the knee angle), tibias 3 kg with the CoM
// 0.2 m below the knee, ankles 0.4 m below the knees, feet 1 kg with the CoM 0.1 m ahead of
// and 0.05 m below the ankle (given in a foot frame turned 90° about z).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>

#include "gaitopt/ident/data_error.hpp"
#include "gaitopt/ident/osim_lumping.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/osim_model_file.hpp"
#include "gaitopt/io/xml_document.hpp"
#include "test_opensim_data.hpp"

using namespace gaitopt;
using Catch::Matchers::Contains;

namespace {

std::string v4Leg(const std::string& side, double femur_mass, double z) {
  const std::string s = "_" + side, zs = std::to_string(z);
  return R"(
  <Body name="femur)" + s + R"("><mass>)" + std::to_string(femur_mass) + R"(</mass><mass_center>0 -0.2 0</mass_center><inertia>0.1 0.02 0.15 0 0 0</inertia></Body>
  <Body name="patella)" + s + R"("><mass>0.1</mass><mass_center>0 0 0</mass_center><inertia>0 0 0 0 0 0</inertia></Body>
  <Body name="tibia)" + s + R"("><mass>3</mass><mass_center>0 -0.2 0</mass_center><inertia>0.04 0.004 0.05 0 0 0</inertia></Body>
  <Body name="calcn)" + s + R"("><mass>1</mass><mass_center>-0.05 -0.1 0</mass_center><inertia>0.002 0.01 0.01 0 0 0</inertia></Body>)";
}

std::string v4LegJoints(const std::string& side, double z) {
  const std::string s = "_" + side, zs = std::to_string(z);
  return R"(
  <PinJoint name="hip)" + s + R"("><socket_parent_frame>pelvis_offset</socket_parent_frame><socket_child_frame>/bodyset/femur)" + s + R"(</socket_child_frame>
    <coordinates><Coordinate name="hip_flexion)" + s + R"("><default_value>0.3</default_value></Coordinate></coordinates>
    <frames><PhysicalOffsetFrame name="pelvis_offset"><socket_parent>/bodyset/pelvis</socket_parent><translation>0 -0.1 )" + zs + R"(</translation><orientation>0 0 0</orientation></PhysicalOffsetFrame></frames></PinJoint>
  <CustomJoint name="knee)" + s + R"("><socket_parent_frame>/bodyset/femur)" + s + R"(</socket_parent_frame><socket_child_frame>tibia_offset</socket_child_frame>
    <coordinates><Coordinate name="knee_angle)" + s + R"("><default_value>-0.5</default_value></Coordinate></coordinates>
    <frames><PhysicalOffsetFrame name="tibia_offset"><socket_parent>/bodyset/tibia)" + s + R"(</socket_parent><translation>0 0 0</translation><orientation>0 0 0</orientation></PhysicalOffsetFrame></frames>
    <SpatialTransform>
      <TransformAxis name="rotation1"><coordinates>knee_angle)" + s + R"(</coordinates><axis>0 0 1</axis><LinearFunction name="function"><coefficients>1 0</coefficients></LinearFunction></TransformAxis>
      <TransformAxis name="rotation2"><coordinates></coordinates><axis>0 1 0</axis><Constant name="function"><value>0</value></Constant></TransformAxis>
      <TransformAxis name="translation2"><coordinates>tib_ty)" + s + R"(</coordinates><axis>0 1 0</axis><LinearFunction name="function"><coefficients>1 0</coefficients></LinearFunction></TransformAxis>
    </SpatialTransform></CustomJoint>
  <WeldJoint name="patellofemoral)" + s + R"("><socket_parent_frame>femur_offset</socket_parent_frame><socket_child_frame>/bodyset/patella)" + s + R"(</socket_child_frame>
    <frames><PhysicalOffsetFrame name="femur_offset"><socket_parent>/bodyset/femur)" + s + R"(</socket_parent><translation>0.05 -0.4 0</translation></PhysicalOffsetFrame></frames></WeldJoint>
  <PinJoint name="ankle)" + s + R"("><socket_parent_frame>tibia_offset</socket_parent_frame><socket_child_frame>/bodyset/calcn)" + s + R"(</socket_child_frame>
    <frames><PhysicalOffsetFrame name="tibia_offset"><socket_parent>/bodyset/tibia)" + s + R"(</socket_parent><translation>0 -0.4 0</translation><orientation>0 0 1.5707963267948966</orientation></PhysicalOffsetFrame></frames></PinJoint>)";
}

// The knee's y translation follows the knee angle through a coupler (OpenSim 3 model: through
// the transform function itself); a disabled coupler must change nothing.
std::string v4Couplers(const std::string& side) {
  const std::string s = "_" + side;
  return R"(
  <CoordinateCouplerConstraint name="knee_ty)" + s + R"("><isEnforced>true</isEnforced>
    <coupled_coordinates_function><SimmSpline><x>-1 0 1 2</x><y>-0.21 -0.2 -0.205 -0.22</y></SimmSpline></coupled_coordinates_function>
    <independent_coordinate_names>knee_angle)" + s + R"(</independent_coordinate_names><dependent_coordinate_name>tib_ty)" + s + R"(</dependent_coordinate_name>
    <scale_factor>2</scale_factor></CoordinateCouplerConstraint>
  <CoordinateCouplerConstraint name="off)" + s + R"("><isEnforced>false</isEnforced>
    <coupled_coordinates_function><Constant><value>5</value></Constant></coupled_coordinates_function>
    <independent_coordinate_names>knee_angle)" + s + R"(</independent_coordinate_names><dependent_coordinate_name>tib_ty)" + s + R"(</dependent_coordinate_name></CoordinateCouplerConstraint>)";
}

std::string v4Model() {
  return R"(<?xml version="1.0" encoding="UTF-8" ?>
<OpenSimDocument Version="40000"><Model name="tiny">
 <gravity>0 -9.81 0</gravity>
 <BodySet name="bodyset"><objects>
  <Body name="pelvis"><mass>10</mass><mass_center>0 0 0</mass_center><inertia>0.1 0.1 0.1 0 0 0</inertia></Body>
  <Body name="torso"><mass>20</mass><mass_center>0 0.3 0</mass_center><inertia>1 0.5 1 0 0 0</inertia></Body>)" +
         v4Leg("r", 8.0, 0.08) + v4Leg("l", 8.2, -0.08) + R"(
 </objects></BodySet>
 <JointSet name="jointset"><objects>
  <FreeJoint name="ground_pelvis"><socket_parent_frame>/ground</socket_parent_frame><socket_child_frame>/bodyset/pelvis</socket_child_frame>
    <coordinates><Coordinate name="pelvis_ty"><default_value>0.9</default_value></Coordinate></coordinates></FreeJoint>
  <PinJoint name="back"><socket_parent_frame>pelvis_offset</socket_parent_frame><socket_child_frame>/bodyset/torso</socket_child_frame>
    <frames><PhysicalOffsetFrame name="pelvis_offset"><socket_parent>/bodyset/pelvis</socket_parent><translation>-0.1 0.1 0</translation><orientation>0 0 0</orientation></PhysicalOffsetFrame></frames></PinJoint>)" +
         v4LegJoints("r", 0.08) + v4LegJoints("l", -0.08) + R"(
 </objects></JointSet>
 <ConstraintSet name="constraintset"><objects>)" + v4Couplers("r") + v4Couplers("l") + R"(
 </objects></ConstraintSet>
</Model></OpenSimDocument>
)";
}

std::string v3Leg(const std::string& side, double femur_mass, double z) {
  const std::string s = "_" + side, zs = std::to_string(z);
  return R"(
  <Body name="femur)" + s + R"("><mass>)" + std::to_string(femur_mass) + R"(</mass><mass_center>0 -0.2 0</mass_center>
    <inertia_xx>0.1</inertia_xx><inertia_yy>0.02</inertia_yy><inertia_zz>0.15</inertia_zz><inertia_xy>0</inertia_xy><inertia_xz>0</inertia_xz><inertia_yz>0</inertia_yz>
    <Joint><PinJoint name="hip)" + s + R"("><parent_body>pelvis</parent_body><location_in_parent>0 -0.1 )" + zs + R"(</location_in_parent><orientation_in_parent>0 0 0</orientation_in_parent><location>0 0 0</location><orientation>0 0 0</orientation>
      <CoordinateSet><objects><Coordinate name="hip_flexion)" + s + R"("><default_value>0.3</default_value></Coordinate></objects></CoordinateSet></PinJoint></Joint></Body>
  <Body name="patella)" + s + R"("><mass>0.1</mass><mass_center>0 0 0</mass_center>
    <Joint><WeldJoint name="patellofemoral)" + s + R"("><parent_body>femur)" + s + R"(</parent_body><location_in_parent>0.05 -0.4 0</location_in_parent></WeldJoint></Joint></Body>
  <Body name="tibia)" + s + R"("><mass>3</mass><mass_center>0 -0.2 0</mass_center><inertia_zz>0.05</inertia_zz>
    <Joint><CustomJoint name="knee)" + s + R"("><parent_body>femur)" + s + R"(</parent_body><location_in_parent>0 0 0</location_in_parent><orientation_in_parent>0 0 0</orientation_in_parent><location>0 0 0</location><orientation>0 0 0</orientation>
      <CoordinateSet><objects><Coordinate name="knee_angle)" + s + R"("><default_value>-0.5</default_value></Coordinate></objects></CoordinateSet>
      <SpatialTransform>
        <TransformAxis name="rotation1"><coordinates>knee_angle)" + s + R"(</coordinates><axis>0 0 1</axis><function><LinearFunction><coefficients>1 0</coefficients></LinearFunction></function></TransformAxis>
        <TransformAxis name="translation2"><coordinates>knee_angle)" + s + R"(</coordinates><axis>0 1 0</axis>
          <function><MultiplierFunction><function><SimmSpline><x>-1 0 1 2</x><y>-0.21 -0.2 -0.205 -0.22</y></SimmSpline></function><scale>2</scale></MultiplierFunction></function></TransformAxis>
      </SpatialTransform></CustomJoint></Joint></Body>
  <Body name="calcn)" + s + R"("><mass>1</mass><mass_center>-0.05 -0.1 0</mass_center><inertia_zz>0.01</inertia_zz>
    <Joint><PinJoint name="ankle)" + s + R"("><parent_body>tibia)" + s + R"(</parent_body><location_in_parent>0 -0.4 0</location_in_parent><orientation_in_parent>0 0 1.5707963267948966</orientation_in_parent><location>0 0 0</location><orientation>0 0 0</orientation></PinJoint></Joint></Body>)";
}

std::string v3Model() {
  return R"(<?xml version="1.0" encoding="UTF-8" ?>
<OpenSimDocument Version="30000"><Model name="tiny">
 <gravity>0 -9.81 0</gravity>
 <BodySet><objects>
  <Body name="ground"><mass>0</mass><Joint /></Body>
  <Body name="pelvis"><mass>10</mass><mass_center>0 0 0</mass_center><inertia_xx>0.1</inertia_xx><inertia_yy>0.1</inertia_yy><inertia_zz>0.1</inertia_zz>
    <Joint><FreeJoint name="ground_pelvis"><parent_body>ground</parent_body><location_in_parent>0 0 0</location_in_parent></FreeJoint></Joint></Body>
  <Body name="torso"><mass>20</mass><mass_center>0 0.3 0</mass_center><inertia_zz>1</inertia_zz>
    <Joint><PinJoint name="back"><parent_body>pelvis</parent_body><location_in_parent>-0.1 0.1 0</location_in_parent></PinJoint></Joint></Body>)" +
         v3Leg("r", 8.0, 0.08) + v3Leg("l", 8.2, -0.08) + R"(
 </objects></BodySet>
</Model></OpenSimDocument>
)";
}

OsimModel parsed(const std::string& text) { return parseOsimModel(parseXml(text, "tiny.osim"), "tiny.osim"); }

// The lumped values of the tiny model, by hand (see the file comment).
void checkTinyLumping(const OsimLumping& l) {
  // Right femur lump: femur 8 kg at (0, -0.3), patella 0.1 kg at (0.05, -0.5); hip (0, -0.1).
  const double mf = 8.1, fx = 0.1 * 0.05 / mf, fy = (8.0 * -0.3 + 0.1 * -0.5) / mf;
  CHECK(l.femur[0].mass == Approx(mf));
  CHECK(l.femur[0].length == Approx(0.4));
  CHECK(l.femur[0].com == Approx(-0.1 - fy));
  CHECK(l.femur[0].com_normal == Approx(fx));
  CHECK(l.femur[0].inertia ==
        Approx(0.15 + 8.0 * (fx * fx + (-0.3 - fy) * (-0.3 - fy)) + 0.1 * ((0.05 - fx) * (0.05 - fx) + (-0.5 - fy) * (-0.5 - fy))));
  CHECK(l.femur[1].mass == Approx(8.3));
  CHECK(l.femur[0].bodies == std::vector<std::string>{"femur_r", "patella_r"});
  // Right tibia lump: tibia 3 kg at (0, -0.7), foot 1 kg at (0.1, -0.95); knee (0, -0.5).
  const double tx = 0.1 / 4.0, ty = (3.0 * -0.7 + 1.0 * -0.95) / 4.0;
  CHECK(l.tibia[0].mass == Approx(4.0));
  CHECK(l.tibia[0].length == Approx(0.4));
  CHECK(l.tibia[0].com == Approx(-0.5 - ty));
  CHECK(l.tibia[0].com_normal == Approx(tx));
  CHECK(l.tibia[0].inertia ==
        Approx(0.05 + 0.01 + 3.0 * (tx * tx + (-0.7 - ty) * (-0.7 - ty)) + 1.0 * ((0.1 - tx) * (0.1 - tx) + (-0.95 - ty) * (-0.95 - ty))));
  CHECK(l.tibia[0].bodies == std::vector<std::string>{"calcn_r", "tibia_r"});
  // Trunk: pelvis 10 kg at (0, 0), torso 20 kg at (-0.1, 0.4); hip midpoint (0, -0.1).
  const double cx = 20.0 * -0.1 / 30.0, cy = 20.0 * 0.4 / 30.0;
  CHECK(l.trunk.mass == Approx(30.0));
  CHECK(l.trunk_com_forward == Approx(cx));
  CHECK(l.trunk_com_up == Approx(cy + 0.1));
  CHECK(l.trunk.com == Approx(std::hypot(cx, cy + 0.1)));
  CHECK(l.trunk.inertia == Approx(0.1 + 1.0 + 10.0 * (cx * cx + cy * cy) + 20.0 * ((-0.1 - cx) * (-0.1 - cx) + (0.4 - cy) * (0.4 - cy))));
  CHECK(l.model_mass == Approx(30.0 + 2 * (0.1 + 3.0 + 1.0) + 8.0 + 8.2));
  CHECK(l.gravity == Approx(9.81));
  CHECK(l.out_of_plane == Approx(0.0).margin(1e-12));
  // The femur mass differs most between the sides: (8.3 - 8.1) / 8.2.
  CHECK(l.asymmetry_quantity == "femur mass");
  CHECK(l.asymmetry == Approx(0.2 / 8.2));
  // The robot: legs averaged, the five masses add up to the model.
  const RobotParams& r = l.robot;
  CHECK(r.mass[1] == Approx(8.2));
  CHECK(r.mass[3] == r.mass[1]);
  CHECK(r.mass[0] + r.mass[1] + r.mass[2] + r.mass[3] + r.mass[4] == Approx(l.model_mass));
  CHECK(r.l1 == Approx(0.4));
  CHECK(r.l2 == Approx(0.4));
  CHECK(r.s[0] == Approx(-0.5 - ty));
  CHECK(r.s[2] == Approx(l.trunk.com));
  CHECK(r.inertia[0] == Approx(l.tibia[0].inertia));
  CHECK(r.gravity == Approx(9.81));
  CHECK(r.rotor_inertia == std::array<double, 4>{});
}

}  // namespace

TEST_CASE("osim lumping: a hand-worked OpenSim 4 model", "[osim]") {
  const OsimModel m = parsed(v4Model());
  CHECK(m.version == 40000);
  CHECK(m.bodies.size() == 10);
  CHECK(m.joints.size() == 10);
  // Default coordinate values are read but the lumping is at zero angles.
  CHECK(m.joints[0].coordinates.at(0).default_value == 0.9);
  REQUIRE(m.couplers.size() == 2);  // the disabled ones are left out
  CHECK(m.couplers[0].dependent == "tib_ty_r");
  CHECK(m.couplers[0].independent == "knee_angle_r");
  CHECK(m.couplers[0].scale == 2.0);
  checkTinyLumping(lumpOsimModel(m));
}

TEST_CASE("osim lumping: the same model in the OpenSim 3 layout", "[osim]") {
  const OsimModel m = parsed(v3Model());
  CHECK(m.version == 30000);
  CHECK(m.bodies.size() == 10);  // ground is not a body
  checkTinyLumping(lumpOsimModel(m));
}

TEST_CASE("osim lumping: thighs named by the caller, and what cannot be lumped", "[osim]") {
  const OsimModel m = parsed(v4Model());
  // Swapping the sides swaps the per-side lumps and keeps the averaged robot.
  const OsimLumping swapped = lumpOsimModel(m, {"femur_l", "femur_r"});
  CHECK(swapped.femur[0].mass == Approx(8.3));
  CHECK(swapped.robot.mass[1] == Approx(8.2));
  const auto dataError = [&](const OsimModel& model, std::array<std::string, 2> thighs, const std::string& key,
                             const std::string& problem) {
    try {
      lumpOsimModel(model, thighs);
      FAIL("no DataError");
    } catch (const DataError& e) {
      INFO(e.what());
      CHECK(e.file() == "tiny.osim");
      CHECK(e.key() == key);
      CHECK_THAT(std::string(e.what()), Contains(problem));
    }
  };
  dataError(m, {"thigh_r", "femur_l"}, "thigh_r", "no body 'thigh_r'");
  dataError(m, {"femur_r", "femur_r"}, "femur_r", "body 'calcn_r' in both legs");
  dataError(m, {"femur_r", "tibia_l"}, "calcn_l", "no joint below 'calcn_l'");
  OsimModel tilted = m;
  tilted.gravity = {1.0, -9.81, 0.0};
  dataError(tilted, {"femur_r", "femur_l"}, "gravity", "not along -y");
  OsimModel loose = m;
  loose.joints.erase(loose.joints.begin() + 1);  // the back joint: the torso hangs from nothing
  dataError(loose, {"femur_r", "femur_l"}, "torso", "not connected to ground");
}

TEST_CASE("osim reader: bad values are named with the body or joint and the line", "[osim]") {
  test::ScratchDir dir("osim");
  const auto load = [](const std::string& path) { return loadOsimModel(path); };
  const auto damaged = [&](const std::string& from, const std::string& to) {
    const std::string path = dir.fresh("model") + ".osim";
    std::ofstream(path) << test::replacedOnce(v4Model(), from, to);
    return path;
  };
  // Line numbers of the hand-written model: the right femur's body is on line 7, the right hip
  // joint on line 21, the right knee's coupler function on line 54.
  test::requireConfigError(load, damaged("<mass>8.000000</mass>", "<mass>8 kg</mass>"), "femur_r.mass", 7,
                           "not a finite number: 'kg'");
  test::requireConfigError(load, damaged("<mass>8.000000</mass>", "<mass>-8</mass>"), "femur_r.mass", 7, "negative mass");
  test::requireConfigError(load, damaged("<mass_center>0 -0.2 0</mass_center>", "<mass_center>0 -0.2</mass_center>"),
                           "femur_r.mass_center", 7, "2 numbers where 3 are expected");
  test::requireConfigError(load, damaged("<SimmSpline><x>-1 0 1 2</x><y>-0.21 -0.2 -0.205 -0.22</y></SimmSpline>",
                                         "<GCVSpline><x>-1 0 1 2</x></GCVSpline>"),
                           "knee_ty_r.coupled_coordinates_function", 54,
                           "transform function <GCVSpline> is not read");
  test::requireConfigError(load, damaged("<x>-1 0 1 2</x>", "<x>-1 0 0 2</x>"), "knee_ty_r.coupled_coordinates_function.x", 54,
                           "x values must increase strictly");
  test::requireConfigError(load, damaged("<socket_parent>/bodyset/pelvis</socket_parent><translation>0 -0.1",
                                         "<socket_parent>/bodyset/hips</socket_parent><translation>0 -0.1"),
                           "hip_r", 21, "'hips', which is not a body");
  for (const auto& [from, to, problem] : {std::array<std::string, 3>{"</Model>", "</Mode>", "end tag 'Mode' does not match 'Model'"},
                                          {"<OpenSimDocument Version=\"40000\"><Model name=\"tiny\">", "<Document><Model>",
                                           "end tag 'OpenSimDocument' does not match 'Document'"}}) {
    const std::string path = damaged(from, to);
    try {
      load(path);
      FAIL("no ConfigError");
    } catch (const ConfigError& e) {
      CHECK_THAT(std::string(e.what()), Contains(path + ":") && Contains(problem));
    }
  }
  const std::string other = dir.fresh("model") + ".osim";
  std::ofstream(other) << "<?xml version=\"1.0\"?>\n<Document/>\n";
  try {
    load(other);
    FAIL("no ConfigError");
  } catch (const ConfigError& e) {
    CHECK_THAT(std::string(e.what()), Contains(other + ":2: ") && Contains("the root element is 'Document', not OpenSimDocument"));
  }
}
