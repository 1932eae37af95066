// Exported MJCF and URDF against gaitopt's own model: MuJoCo's mass matrix and bias forces
// (high-gear rotor model = MuJoCo armature) and the URDF's kinematics and inertias.
#include <catch2/catch.hpp>
#include <fstream>

#include "gaitopt/export/robot_export.hpp"
#include "gaitopt/model/dynamics_floating.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

#ifdef GAITOPT_HAVE_MUJOCO
#include <mujoco/mujoco.h>
#endif
#ifdef GAITOPT_HAVE_URDFDOM
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#endif

namespace gaitopt::test {
namespace {

// A floating state X = [q, x_t, z_t] and its rate, both random.
void randomFloatingState(RandomStates& rs, Vector7<double>& X, Vector7<double>& Xd) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  X << rs.q(), u(rs.rng), 0.8 + 0.1 * u(rs.rng);
  Xd << rs.qd(), u(rs.rng), u(rs.rng);
}

}  // namespace

#ifdef GAITOPT_HAVE_MUJOCO
TEST_CASE("MJCF in MuJoCo: mass matrix and bias forces equal gaitopt's high-gear model",
          "[export][mujoco]") {
  for (const char* robot : {"rabbit_miossec", "rabbit_miossec_nobar", "rabbit_chesse"}) {
    INFO(robot);
    const RobotParams params = robotFile(robot);
    ModelOptions options;
    options.rotor = RotorModel::HighGear;
    const Model model = buildModel(params, options);
    ScratchDir dir("mjcf");
    const std::string path = dir.fresh("robot") + ".xml";
    std::ofstream(path) << robotMjcf(params);
    char error[1000] = "";
    mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
    INFO(error);
    REQUIRE(m != nullptr);
    REQUIRE(m->nv == 7);
    mjData* d = mj_makeData(m);
    const Eigen::Matrix<double, 7, 7> L = mjcfCoordinateMap();
    RandomStates rs;
    const int foot_left = mj_name2id(m, mjOBJ_SITE, "foot_left");
    const int foot_right = mj_name2id(m, mjOBJ_SITE, "foot_right");
    for (int trial = 0; trial < 20; ++trial) {
      Vector7<double> X, Xd;
      randomFloatingState(rs, X, Xd);
      Eigen::Map<Eigen::Matrix<double, 7, 1>>(d->qpos) = L * X;
      Eigen::Map<Eigen::Matrix<double, 7, 1>>(d->qvel) = L * Xd;
      mj_forward(m, d);
      Eigen::Matrix<double, 7, 7, Eigen::RowMajor> M;
      mj_fullM(m, M.data(), d->qM);
      const Eigen::Matrix<double, 7, 1> bias = Eigen::Map<Eigen::Matrix<double, 7, 1>>(d->qfrc_bias);
      const FloatingTerms<double> t = floatingTerms(model, X, Xd);
      // Same kinetic and potential energy in both coordinates: A = Lᵀ M L, C + G = Lᵀ bias.
      CHECK((L.transpose() * M * L - t.A).lpNorm<Eigen::Infinity>() < 1e-9);
      CHECK((L.transpose() * bias - (t.C + t.G)).lpNorm<Eigen::Infinity>() < 1e-9);
      const ChainState<double> st = chainState(model, Vec5(X.head<5>()), Vec5(Xd.head<5>()));
      const Vec2 trunk = X.tail<2>();
      const Vec2 f1 = trunk + chainPoint(model.floating.foot1, st);
      const Vec2 f2 = trunk + chainPoint(model.floating.foot2, st);
      CHECK(Vec2(d->site_xpos[3 * foot_left], d->site_xpos[3 * foot_left + 2]).isApprox(f1, 1e-12));
      CHECK(Vec2(d->site_xpos[3 * foot_right], d->site_xpos[3 * foot_right + 2])
                .isApprox(f2, 1e-12));
    }
    mj_deleteData(d);
    mj_deleteModel(m);
  }
}
#endif

#ifdef GAITOPT_HAVE_URDFDOM
namespace {

Eigen::Isometry3d poseOf(const urdf::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() << p.position.x, p.position.y, p.position.z;
  T.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                   .toRotationMatrix();
  return T;
}

// Pose of `link` in the trunk frame with the revolute joints at `values`.
Eigen::Isometry3d linkPose(const urdf::ModelInterface& u, const std::string& link,
                           const std::map<std::string, double>& values) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (auto l = u.getLink(link); l->name != "trunk"; l = l->getParent()) {
    const urdf::Joint& j = *l->parent_joint;
    const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
    T = poseOf(j.parent_to_joint_origin_transform) *
        Eigen::AngleAxisd(values.at(j.name), axis) * T;
  }
  return T;
}

}  // namespace

TEST_CASE("URDF parsed by urdfdom: kinematics, masses and inertias equal gaitopt's model",
          "[export][urdf]") {
  const RobotParams params = robotFile("rabbit_miossec");
  const Model model = buildModel(params);
  const urdf::ModelInterfaceSharedPtr u = urdf::parseURDF(robotUrdf(params));
  REQUIRE(u != nullptr);
  REQUIRE(u->getJoint("root")->type == urdf::Joint::PLANAR);
  double mass = 0.0;
  std::vector<urdf::LinkSharedPtr> links;
  u->getLinks(links);
  for (const auto& l : links)
    if (l->inertial) mass += l->inertial->mass;
  CHECK(mass == Approx(model.total_mass).epsilon(1e-15));
  CHECK(u->getLink("tibia_left")->inertial->iyy == params.inertia[0]);
  CHECK(u->getLink("femur_right")->inertial->iyy == params.inertia[3]);
  CHECK(u->getJoint("knee_left")->limits->lower == params.limits.knee_min);
  CHECK(u->getJoint("hip_right")->limits->upper == -params.limits.hip_min);
  RandomStates rs;
  for (int trial = 0; trial < 20; ++trial) {
    const Vec5 q = rs.q();
    const Vec4 phi(q(1), -q(2), -(q(2) + q(3)), q(4));  // φ = D_Γᵀ q
    const std::map<std::string, double> values{{"knee_left", phi(0)}, {"hip_left", phi(1)},
                                               {"hip_right", phi(2)}, {"knee_right", phi(3)},
                                               {"support_bar", 0.0}};
    // Trunk frame in the plane: rotated by θ3 − π/2 (x toward z), i.e. about −y.
    const Eigen::Isometry3d trunk(
        Eigen::AngleAxisd(q(0) + q(1) - q(2), Eigen::Vector3d(0, -1, 0)));
    const ChainState<double> st = chainState(model, q, Vec5(Vec5::Zero()));
    const auto planar = [](const Eigen::Vector3d& p) { return Vec2(p.x(), p.z()); };
    const auto point = [&](const std::string& link, double z) {
      return planar(trunk * linkPose(*u, link, values) * Eigen::Vector3d(0, 0, z));
    };
    CHECK(point("tibia_left", params.l1).isApprox(chainPoint(model.floating.foot1, st), 1e-12));
    CHECK(point("tibia_right", params.l5).isApprox(chainPoint(model.floating.foot2, st), 1e-12));
    // Whole-body CoM relative to the trunk-with-bar CoM.
    Vec2 com = Vec2::Zero();
    for (const auto& l : links)
      if (l->inertial)
        com += l->inertial->mass *
               point(l->name, l->inertial->origin.position.z) / model.total_mass;
    CHECK(com.isApprox(chainPoint(model.floating.b, st) / model.total_mass, 1e-12));
  }
}
#endif

}  // namespace gaitopt::test
