#include "gaitopt/model/model.hpp"

#include <cmath>

#include "gaitopt/model/support_bar.hpp"

namespace gaitopt {
namespace {

// Rotor speed rows w_j (ω_mj = w_j q̇), from (1.17) with (1.13).
Eigen::Matrix<double, 4, 5> rotorSpeedRows(double N, RotorModel rotor) {
  Eigen::Matrix<double, 4, 5> w;
  if (rotor == RotorModel::Exact) {
    w << 1, 1 - N, 0, 0, 0,   //
        1, 1, N - 1, 0, 0,    //
        1, 1, N - 1, N, 0,    //
        1, 1, 0, 1, -N;
  } else {  // (A.1): only N × the joint relative speed
    w << 0, N, 0, 0, 0,  //
        0, 0, N, 0, 0,   //
        0, 0, N, N, 0,   //
        0, 0, 0, 0, N;
  }
  return w;
}

ChainCoefficients chainCoefficients(const Mat5& body, const Vec5& foot1, const Vec5& foot2,
                                    const Vec5& hip, const Vec5& mass) {
  ChainCoefficients c;
  c.body = body;
  c.foot1 = foot1;
  c.foot2 = foot2;
  c.hip = hip;
  c.P = body.transpose() * mass.asDiagonal() * body;
  c.b = body.transpose() * mass;
  return c;
}

}  // namespace

Model buildModel(const RobotParams& robot, const ModelOptions& options) {
  Model m;
  m.robot = robot;
  m.options = options;
  for (int i = 0; i < 5; ++i) {
    m.mass(i) = robot.mass[i];
    m.com_offset(i) = robot.s[i];
    m.inertia(i) = robot.inertia[i];
  }
  m.com_offset(2) += robot.trunk_com_shift;
  if (robot.bar.present || robot.hip_payload != 0.0) {
    // A payload at the hip folds in exactly like the bar's equivalent mass (1.24).
    const double hip_mass = (robot.bar.present ? robot.bar.equivalent_mass : 0.0) +
                            robot.hip_payload;
    const TrunkParameters t =
        trunkWithBar(robot.mass[2], m.com_offset(2), robot.inertia[2], hip_mass);
    m.mass(2) = t.mass;
    m.com_offset(2) = t.com_offset;
    m.inertia(2) = t.inertia;
  }
  m.total_mass = m.mass.sum();
  m.gravity = robot.gravity;

  // (1.13): θ1 = α − π/2, θ2 = α+δ1+π/2, θ3 = α+δ1−δ2+π/2, θ4 = α+δ1+δ3+π/2,
  // θ5 = α+δ1+δ3−δ4−π/2.
  m.theta_map << 1, 0, 0, 0, 0,  //
      1, 1, 0, 0, 0,             //
      1, 1, -1, 0, 0,            //
      1, 1, 0, 1, 0,             //
      1, 1, 0, 1, -1;
  m.theta_map_transpose = m.theta_map.transpose();
  const double h = 0.5 * M_PI;
  m.theta_offset << -h, h, h, h, -h;

  // (1.37), (1.38): positions from foot 1 along u(θ1)..u(θ5).
  const double l1 = robot.l1, l2 = robot.l2, l4 = robot.l4, l5 = robot.l5;
  const Vec5& s = m.com_offset;
  Mat5 body;
  body << -(l1 - s(0)), 0, 0, 0, 0,  //
      -l1, -(l2 - s(1)), 0, 0, 0,    //
      -l1, -l2, s(2), 0, 0,          //
      -l1, -l2, 0, s(3), 0,          //
      -l1, -l2, 0, l4, s(4);
  Vec5 foot1 = Vec5::Zero();
  Vec5 foot2, hip;
  foot2 << -l1, -l2, 0, l4, l5;
  hip << -l1, -l2, 0, 0, 0;
  m.pinned = chainCoefficients(body, foot1, foot2, hip, m.mass);

  // (1.14), (1.15): the same points relative to the trunk CoM.
  const Vec5 trunk = body.row(2).transpose();
  Mat5 body_f = body.rowwise() - trunk.transpose();
  m.floating = chainCoefficients(body_f, foot1 - trunk, foot2 - trunk, hip - trunk, m.mass);

  const Eigen::Matrix<double, 4, 5> w = rotorSpeedRows(robot.gear_ratio, options.rotor);
  m.rotor_inertia_matrix.setZero();
  for (int j = 0; j < 4; ++j)
    m.rotor_inertia_matrix += robot.rotor_inertia[j] * w.row(j).transpose() * w.row(j);

  // (1.19): δW = δδ1 Γ1 − δδ2 Γ2 − (δδ3 + δδ2) Γ3 + δδ4 Γ4.
  m.D_Gamma << 0, 0, 0, 0,  //
      1, 0, 0, 0,           //
      0, -1, -1, 0,         //
      0, 0, -1, 0,          //
      0, 0, 0, 1;
  for (int j = 0; j < 4; ++j) {
    m.coulomb(j) = robot.coulomb[j];
    m.viscous(j) = robot.viscous[j];
  }
  return m;
}

}  // namespace gaitopt
