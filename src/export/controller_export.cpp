#include "gaitopt/export/controller_export.hpp"

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/controller_export_file.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/file_digest.hpp"
#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/gait/boundary_geometry.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/inverse_dynamics.hpp"

#ifndef GAITOPT_VERSION
#define GAITOPT_VERSION "unknown"
#endif

namespace gaitopt {
namespace {

// Leg-1 labels (knee 1, hip 1, hip 2, knee 2) to physical order: identity when leg 1 is the
// left leg, reversed when it is the right one.
Vec4 toPhysical(const Vec4& v, Leg leg1) { return leg1 == Leg::Left ? v : Vec4(v.reverse()); }

Vec4 motorAngles(const Vec5& q) { return jointSpeeds(q); }  // φ = D_Γᵀ q, linear like ω

// Γ* of a sampled motion split as D_Γ25⁻¹ of (A q̈ + C), G and −D2ᵀ R2 (rows 2–5 of (1.32)),
// plus the friction (1.21) of `model`.
struct TorqueParts {
  Vec4 inertial, gravity, contact, friction;
};

TorqueParts torqueParts(const Model& model, const TrajectoryRow& r) {
  const ChainState<double> st = chainState(model, r.q, r.qd);
  const PinnedMotionForces<double> f = pinnedMotionForces(model, st, r.qdd);
  const Vec5 G = constantTimes(model.theta_map_transpose,
                               chainGravityTheta(model.pinned, model.gravity, st));
  const Vec5 contact = -f.D2.transpose() * r.R2;
  TorqueParts p;
  p.inertial = solveDGamma25(Vec4((f.tau - G).tail<4>()));
  p.gravity = solveDGamma25(Vec4(G.tail<4>()));
  p.contact = solveDGamma25(Vec4(contact.tail<4>()));
  p.friction = frictionTorque(model, jointSpeeds(r.qd), SignMode::Smooth);
  return p;
}

// q, dq/dα, d²q/dα² of a phase's path at α.
struct PathDerivatives {
  Vec5 q, qa, qaa;
};

// SS: (α, δ(α)) on the virtual constraints (3.2).
PathDerivatives ssPathDerivatives(const GaitMotion<double>& mo, double alpha) {
  PathDerivatives p;
  p.q(0) = alpha;
  p.qa(0) = 1.0;
  p.qaa(0) = 0.0;
  for (int j = 0; j < 4; ++j) {
    const PolyValue<double> v = mo.ss_path[j](alpha);
    p.q(j + 1) = v.value;
    p.qa(j + 1) = v.first;
    p.qaa(j + 1) = v.second;
  }
  return p;
}

// DS: δ1, δ2 on the front leg's curves (3.3), δ3, δ4 from the closed chain with the rear foot
// fixed, whose velocity and acceleration vanish (1.34), (1.35) taken per unit α̇ with α̈ = 0.
PathDerivatives dsPathDerivatives(const Model& m, const GaitMotion<double>& mo, double alpha) {
  const PolyValue<double> d1 = mo.ds_delta1(alpha), d2 = mo.ds_delta2(alpha);
  const Vec2 rear =
      leg2InverseKinematics(m, alpha, d1.value, rearFootFromHip(m, alpha, d1.value, mo.d));
  PathDerivatives p;
  p.q << alpha, d1.value, d2.value, rear(0), rear(1);
  ChainState<double> st = chainState(m, p.q, Vec5(Vec5::Zero()));
  const Matrix25<double> D2 = chainPointJacobian(m, m.pinned.foot2, st);
  const Eigen::Matrix2d rear_columns = D2.rightCols<2>();
  const Eigen::Matrix2d rear_inverse = rear_columns.inverse();
  const Vec2 rear_rate = -rear_inverse * (D2.col(0) + D2.col(1) * d1.first);
  p.qa << 1.0, d1.first, d2.first, rear_rate(0), rear_rate(1);
  st.theta_dot = constantTimes(m.theta_map, p.qa);
  const Vec2 rear_curvature =
      -rear_inverse * (D2.col(1) * d1.second + chainPointBias(m.pinned.foot2, st));
  p.qaa << 0.0, d1.second, d2.second, rear_curvature(0), rear_curvature(1);
  return p;
}

Leg otherLeg(Leg l) { return l == Leg::Left ? Leg::Right : Leg::Left; }

// A phase of a walk between two boundaries: step, phase, start and end time, foot 1 index.
struct PhaseSpan {
  std::size_t step;
  Phase phase;
  double t0, t1;
  int foot;  // foot 1 is the walk's foot number `foot` (even: the first stance leg)
};

// The phases walked in order, timed and placed as sampleWalk does.
std::vector<PhaseSpan> phaseSpans(const std::vector<WalkStepMotion>& walk) {
  std::vector<PhaseSpan> spans;
  double t = 0.0;
  int ss_before = 0;
  for (std::size_t k = 0; k < walk.size(); ++k) {
    const GaitEvaluation<double>& e = *walk[k].evaluation;
    if (walk[k].single_support) {
      spans.push_back({k, Phase::SingleSupport, t, t + e.T_SS, ss_before});
      t += e.T_SS;
    }
    if (e.motion.T_DS > 0.0) {
      spans.push_back({k, Phase::DoubleSupport, t, t + e.motion.T_DS,
                       ss_before + (walk[k].single_support ? 1 : 0)});
      t += e.motion.T_DS;
    }
    ss_before += walk[k].single_support ? 1 : 0;
  }
  return spans;
}

// The rows of a boundary: the end of `a` then the start of `b`, at a's end time.
std::array<PlannedSample, 2> boundarySamples(const GaitEvaluator& ev,
                                             const std::vector<WalkStepMotion>& walk,
                                             const PhaseSpan& a, const PhaseSpan& b) {
  const auto sample = [&](const PhaseSpan& p, double local) {
    const GaitEvaluation<double>& e = *walk[p.step].evaluation;
    return PlannedSample{a.t1, static_cast<int>(p.step), e.motion.d * p.foot, p.foot % 2 == 0,
                         sampleTrajectoryAt(ev, e, p.phase, local)};
  };
  return {sample(a, a.t1 - a.t0), sample(b, 0.0)};
}

// Event rows inserted among the fixed-rate rows (both in time order): a fixed-rate row at the
// very start of a phase (within 1 ns) is that phase's start row, flagged instead of doubled.
std::vector<ExportRow> withEvents(const std::vector<ExportRow>& fixed,
                                  const std::vector<ExportRow>& events) {
  constexpr double kSameInstant = 1e-9;  // s
  std::vector<ExportRow> out;
  out.reserve(fixed.size() + events.size());
  std::size_t j = 0;
  for (ExportRow f : fixed) {
    bool written = false;
    while (j < events.size() && events[j].t < f.t + kSameInstant) {
      const ExportRow& e = events[j++];
      const bool is_f = !written && std::abs(e.t - f.t) <= kSameInstant && e.step == f.step &&
                        e.phase == f.phase;
      if (is_f) f.event = e.event;
      out.push_back(is_f ? f : e);
      written = written || is_f;
    }
    if (!written) out.push_back(f);
  }
  out.insert(out.end(), events.begin() + static_cast<long>(j), events.end());
  return out;
}

const char* legName(Leg l) { return l == Leg::Left ? "left" : "right"; }
const char* phaseName(Phase p) { return p == Phase::SingleSupport ? "SS" : "DS"; }

// Numeric columns after t, step, phase, stance: name, unit and the field they read/write.
struct NumericColumn {
  std::string name, unit;
  std::function<double&(ExportRow&)> field;
};

std::vector<NumericColumn> numericColumns() {
  std::vector<NumericColumn> c = {
      {"s", "-", [](ExportRow& r) -> double& { return r.s; }},
      {"sd", "1/s", [](ExportRow& r) -> double& { return r.sd; }},
      {"sdd", "1/s^2", [](ExportRow& r) -> double& { return r.sdd; }},
      {"alpha", "rad", [](ExportRow& r) -> double& { return r.alpha; }},
      {"alphad", "rad/s", [](ExportRow& r) -> double& { return r.alphad; }},
      {"alphadd", "rad/s^2", [](ExportRow& r) -> double& { return r.alphadd; }},
      {"x_hip", "m", [](ExportRow& r) -> double& { return r.hip(0); }},
      {"z_hip", "m", [](ExportRow& r) -> double& { return r.hip(1); }},
      {"trunk_angle", "rad", [](ExportRow& r) -> double& { return r.trunk_angle; }},
  };
  using Field = Vec4 ExportRow::*;
  const std::vector<std::tuple<std::string, std::string, Field>> per_joint = {
      {"phi", "rad", &ExportRow::phi},
      {"phid", "rad/s", &ExportRow::phid},
      {"phidd", "rad/s^2", &ExportRow::phidd},
      {"motor", "rad", &ExportRow::motor},
      {"tau", "N*m", &ExportRow::tau},
      {"tau_inertial", "N*m", &ExportRow::tau_inertial},
      {"tau_gravity", "N*m", &ExportRow::tau_gravity},
      {"tau_contact", "N*m", &ExportRow::tau_contact},
      {"tau_friction", "N*m", &ExportRow::tau_friction},
      {"tau_B", "N*m", &ExportRow::tau_B},
      {"tau_C", "N*m", &ExportRow::tau_C}};
  for (int j = 0; j < 4; ++j)
    for (const auto& [name, unit, field] : per_joint)
      c.push_back({name + "_" + kPhysicalJoints[j], unit,
                   [field = field, j](ExportRow& r) -> double& { return (r.*field)(j); }});
  using Point = Vec2 ExportRow::*;
  const std::vector<std::tuple<std::string, std::string, Point>> points = {
      {"foot_left", "m", &ExportRow::foot_left},
      {"foot_right", "m", &ExportRow::foot_right},
      {"R_left", "N", &ExportRow::R_left},
      {"R_right", "N", &ExportRow::R_right}};
  for (const auto& [name, unit, field] : points)
    for (int i = 0; i < 2; ++i)
      c.push_back({name + (i == 0 ? "_x" : "_z"), unit,
                   [field = field, i](ExportRow& r) -> double& { return (r.*field)(i); }});
  return c;
}

void writePolynomial(JsonWriter& w, const std::string& name, const std::vector<double>& a) {
  w.key(name).beginObject();
  w.key("monomial").value(Eigen::Map<const Eigen::VectorXd>(a.data(), a.size()));
  const std::vector<double> b = bezierFromMonomials(a);
  w.key("bezier").value(Eigen::Map<const Eigen::VectorXd>(b.data(), b.size()));
  w.endObject();
}

// φ_j of the SS outputs as polynomials of α (φ = D_Γᵀ q is linear in δ1..δ4).
std::array<LocalPolynomial<double>, 4> ssMotorPolynomials(const GaitMotion<double>& mo) {
  // δ1..δ4(α), all with x0 = α_iSS (polynomial basis only: a B-spline path throws)
  const std::array<LocalPolynomial<double>, 4> p{mo.ss_path[0].polynomial(), mo.ss_path[1].polynomial(),
                                                 mo.ss_path[2].polynomial(), mo.ss_path[3].polynomial()};
  LocalPolynomial<double> hip2 = p[1];
  hip2.c.resize(std::max(p[1].c.size(), p[2].c.size()), 0.0);
  for (std::size_t k = 0; k < p[2].c.size(); ++k) hip2.c[k] += p[2].c[k];
  std::array<LocalPolynomial<double>, 4> phi{p[0], p[1], hip2, p[3]};
  for (double& c : phi[1].c) c = -c;
  for (double& c : phi[2].c) c = -c;
  return phi;
}

// Leg-1 joint names of a phase, in the order of FeedforwardTerms and of the tables.
std::array<const char*, 4> phaseJoints(Phase phase) {
  if (phase == Phase::SingleSupport)
    return {"knee_stance", "hip_stance", "hip_swing", "knee_swing"};
  return {"knee_front", "hip_front", "hip_rear", "knee_rear"};
}

// Grid of the feedforward tables: s = k / kTableIntervals.
constexpr int kTableIntervals = 100;

// B, C, G, dφ/ds and φ of a phase on the uniform s grid, per leg-1 joint, with the largest
// error of linear interpolation between grid points (checked at the midpoints).
void writeFeedforwardTable(JsonWriter& w, const Model& model, const GaitMotion<double>& mo,
                           Phase phase) {
  // A pair, not a structured binding: C++17 lambdas cannot capture those.
  const std::pair<double, double> range = phaseAlphaRange(mo, phase);
  const auto at = [&](double s) {
    const double alpha = range.first + s * (range.second - range.first);
    const FeedforwardTerms t = feedforwardTerms(model, mo, phase, alpha);
    return std::array<Vec4, 5>{t.B, t.C, t.G, t.dphi_ds, t.phi};
  };
  static const std::array<const char*, 5> names{"B", "C", "G", "dphi_ds", "phi"};
  std::vector<std::array<Vec4, 5>> grid;
  std::array<double, 5> error{};
  for (int k = 0; k <= kTableIntervals; ++k) {
    grid.push_back(at(static_cast<double>(k) / kTableIntervals));
    if (k == 0) continue;
    const std::array<Vec4, 5> mid = at((k - 0.5) / kTableIntervals);
    for (std::size_t i = 0; i < names.size(); ++i)
      error[i] = std::max(error[i], (mid[i] - 0.5 * (grid[k - 1][i] + grid[k][i]))
                                        .lpNorm<Eigen::Infinity>());
  }
  const std::array<const char*, 4> joints = phaseJoints(phase);
  w.key("feedforward_table").beginObject();
  w.key("s").beginArray();
  for (int k = 0; k <= kTableIntervals; ++k) w.value(static_cast<double>(k) / kTableIntervals);
  w.endArray();
  for (std::size_t i = 0; i < names.size(); ++i) {
    w.key(names[i]).beginObject();
    for (int j = 0; j < 4; ++j) {
      w.key(joints[j]).beginArray();
      for (const std::array<Vec4, 5>& g : grid) w.value(g[i](j));
      w.endArray();
    }
    w.endObject();
  }
  w.key("linear_interpolation_max_error").beginObject();
  for (std::size_t i = 0; i < names.size(); ++i) w.key(names[i]).value(error[i]);
  w.endObject();
  w.endObject();
}

// What every phase states: its joints in leg-1 order, its α range and s.
void writePhaseHead(JsonWriter& w, const GaitMotion<double>& mo, Phase phase, double duration) {
  const auto [alpha_start, alpha_end] = phaseAlphaRange(mo, phase);
  w.key("leg1").value(phase == Phase::SingleSupport ? "the stance leg" : "the front leg");
  w.key("joint_order").beginArray();
  for (const char* j : phaseJoints(phase)) w.value(j);
  w.endArray();
  w.key("phase_variable").value("s = (alpha - alpha_start) / (alpha_end - alpha_start)");
  w.key("alpha_start").value(alpha_start);
  w.key("alpha_end").value(alpha_end);
  w.key("duration").value(duration);
}

void writeSsPhase(JsonWriter& w, const Model& model, const GaitMotion<double>& mo) {
  const double h = mo.alpha_fSS - mo.alpha_iSS;
  w.key("SS").beginObject();
  writePhaseHead(w, mo, Phase::SingleSupport, mo.T_SS);
  w.key("alphad_start").value(mo.alphadot_iSS);
  w.key("alphad_end").value(mo.alphadot_fSS);
  w.key("outputs").beginObject();
  const std::array<LocalPolynomial<double>, 4> phi = ssMotorPolynomials(mo);
  static const std::array<const char*, 4> names{"phi_knee_stance", "phi_hip_stance",
                                                "phi_hip_swing", "phi_knee_swing"};
  for (int j = 0; j < 4; ++j) writePolynomial(w, names[j], normalisedMonomials(phi[j], h));
  w.endObject();
  w.key("time_law").value("alpha(t) from the zero dynamics (3.15): alphad and alphadd are in "
                          "the samples");
  writeFeedforwardTable(w, model, mo, Phase::SingleSupport);
  w.endObject();
}

void writeDsPhase(JsonWriter& w, const Model& model, const GaitMotion<double>& mo) {
  const auto [alpha_i, alpha_f] = phaseAlphaRange(mo, Phase::DoubleSupport);
  w.key("DS").beginObject();
  writePhaseHead(w, mo, Phase::DoubleSupport, mo.T_DS);
  w.key("time_variable").value("tau = t / duration, t from touchdown");
  writePolynomial(w, "alpha_of_tau", normalisedMonomials(mo.ds_alpha, mo.T_DS));
  w.key("outputs").beginObject();
  LocalPolynomial<double> hip = mo.ds_delta2.polynomial();
  for (double& c : hip.c) c = -c;
  writePolynomial(w, "phi_knee_front", normalisedMonomials(mo.ds_delta1.polynomial(), alpha_f - alpha_i));
  writePolynomial(w, "phi_hip_front", normalisedMonomials(hip, alpha_f - alpha_i));
  w.endObject();
  w.key("closed_chain").value("phi_hip_rear and phi_knee_rear follow from the rear leg's "
                              "inverse kinematics with the rear foot at (-step_length, 0) "
                              "from the front foot, knee bent forward (3.18)-(3.19); the "
                              "feedforward_table lists them on its grid");
  writeFeedforwardTable(w, model, mo, Phase::DoubleSupport);
  w.endObject();
}

const char* rotorName(RotorModel r) { return r == RotorModel::Exact ? "exact" : "high_gear"; }

// The `# schema_version` line before the header, of the version this reader knows.
void requireCsvSchema(const ExportMetadata& meta, const std::string& path, int line) {
  const auto v = meta.find("schema_version");
  const std::string known = std::to_string(kControllerExportSchema);
  if (v == meta.end())
    throw ConfigError(path, "schema_version", line,
                      "no '# schema_version: " + known +
                          "' line before the header (written by an older gaitopt: export again)");
  if (v->second != known)
    throw ConfigError(path, "schema_version", line,
                      "schema version " + v->second + " is not supported (this gaitopt reads " +
                          known + ")");
}

}  // namespace

ExportRow exportRow(const Model& model, const TrajectoryRow& r, int step, Leg stance,
                    double foot1_x, double t) {
  ExportRow e;
  e.t = t;
  e.step = step;
  e.phase = r.phase;
  e.stance = stance;
  e.alpha = r.q(0);
  e.alphad = r.qd(0);
  e.alphadd = r.qdd(0);
  const ChainState<double> st = chainState(model, r.q, r.qd);
  const Vec2 foot1(foot1_x, 0.0);
  e.hip = chainPoint(model.pinned.hip, st) + foot1;
  e.trunk_angle = r.q(0) + r.q(1) - r.q(2);  // θ3 − π/2 by (1.13)
  e.phi = toPhysical(motorAngles(r.q), stance);
  e.phid = toPhysical(jointSpeeds(r.qd), stance);
  e.phidd = toPhysical(jointSpeeds(r.qdd), stance);
  e.motor = e.phi * model.robot.gear_ratio;
  const TorqueParts p = torqueParts(model, r);
  e.tau_inertial = toPhysical(p.inertial, stance);
  e.tau_gravity = toPhysical(p.gravity, stance);
  e.tau_contact = toPhysical(p.contact, stance);
  e.tau_friction = toPhysical(p.friction, stance);
  e.tau = e.tau_inertial + e.tau_gravity + e.tau_contact + e.tau_friction;
  const Vec2 foot2 = r.foot2 + foot1;
  (stance == Leg::Left ? e.foot_left : e.foot_right) = foot1;
  (stance == Leg::Left ? e.foot_right : e.foot_left) = foot2;
  (stance == Leg::Left ? e.R_left : e.R_right) = r.R1;
  (stance == Leg::Left ? e.R_right : e.R_left) = r.R2;
  return e;
}

std::pair<double, double> phaseAlphaRange(const GaitMotion<double>& mo, Phase phase) {
  if (phase == Phase::SingleSupport) return {mo.alpha_iSS, mo.alpha_fSS};
  return {mo.ds_alpha(0.0).value, mo.ds_alpha(mo.T_DS).value};
}

// With q̇ = q_s ṡ and q̈ = q_s s̈ + q_ss ṡ² on the path, A q̈ + C(q, q̇) q̇ = A q_s s̈ +
// (A q_ss + C(q, q_s) q_s) ṡ², C being quadratic in the speed: two inverse dynamics give both.
FeedforwardTerms feedforwardTerms(const Model& m, const GaitMotion<double>& mo, Phase phase,
                                  double alpha) {
  const auto [alpha_start, alpha_end] = phaseAlphaRange(mo, phase);
  const double h = alpha_end - alpha_start;
  const PathDerivatives p = phase == Phase::SingleSupport ? ssPathDerivatives(mo, alpha)
                                                          : dsPathDerivatives(m, mo, alpha);
  const Vec5 qs = p.qa * h, qss = p.qaa * (h * h);
  const ChainState<double> at_rest = chainState(m, p.q, Vec5(Vec5::Zero()));
  const Vec5 G = constantTimes(m.theta_map_transpose,
                               chainGravityTheta(m.pinned, m.gravity, at_rest));
  const Vec5 acceleration = pinnedMotionForces(m, at_rest, qs).tau - G;
  const Vec5 speed = pinnedMotionForces(m, chainState(m, p.q, qs), qss).tau - G;
  FeedforwardTerms t;
  t.B = solveDGamma25(Vec4(acceleration.tail<4>()));
  t.C = solveDGamma25(Vec4(speed.tail<4>()));
  t.G = solveDGamma25(Vec4(G.tail<4>()));
  t.dphi_ds = jointSpeeds(qs);
  t.phi = motorAngles(p.q);
  return t;
}

void setPhaseTerms(ExportRow& r, const Model& model, const GaitMotion<double>& mo) {
  const auto [alpha_start, alpha_end] = phaseAlphaRange(mo, r.phase);
  const double h = alpha_end - alpha_start;
  r.s = (r.alpha - alpha_start) / h + 0.0;  // + 0.0: s = 0 at the phase start, not −0
  r.sd = r.alphad / h;
  r.sdd = r.alphadd / h;
  const FeedforwardTerms t = feedforwardTerms(model, mo, r.phase, r.alpha);
  r.tau_B = toPhysical(t.B, r.stance);
  r.tau_C = toPhysical(t.C, r.stance);
}

std::vector<ExportRow> exportWalk(const GaitEvaluator& ev, const Model& model,
                                  const std::vector<WalkStepMotion>& walk,
                                  const std::vector<PlannedSample>& samples, Leg first_stance) {
  const auto rowOf = [&](const PlannedSample& s) {
    ExportRow r = exportRow(model, s.row, s.step,
                            s.leg1_is_first_stance ? first_stance : otherLeg(first_stance),
                            s.foot1_x, s.t);
    setPhaseTerms(r, model, walk[static_cast<std::size_t>(s.step)].evaluation->motion);
    return r;
  };
  std::vector<ExportRow> fixed, events;
  fixed.reserve(samples.size());
  for (const PlannedSample& s : samples) fixed.push_back(rowOf(s));
  const std::vector<PhaseSpan> spans = phaseSpans(walk);
  for (std::size_t i = 0; i + 1 < spans.size(); ++i) {
    const ExportEvent event = spans[i].phase == Phase::SingleSupport ? ExportEvent::Touchdown
                                                                     : ExportEvent::LiftOff;
    for (const PlannedSample& s : boundarySamples(ev, walk, spans[i], spans[i + 1])) {
      events.push_back(rowOf(s));
      events.back().event = event;
    }
  }
  return withEvents(fixed, events);
}

std::vector<ExportRow> exportTrajectory(const GaitEvaluator& ev, const GaitEvaluation<double>& e,
                                        const Model& model, const ExportRequest& req) {
  if (req.steps < 1 || !(req.rate > 0.0))
    throw std::invalid_argument("exportTrajectory: steps must be >= 1 and rate > 0");
  const auto step = std::make_shared<const GaitEvaluation<double>>(e);
  const std::vector<WalkStepMotion> walk(req.steps, WalkStepMotion{step, true});
  return exportWalk(ev, model, walk, sampleWalk(ev, walk, req.rate), req.first_stance);
}

ExportMetadata exportMetadata(const GaitFile& gait, const GaitEvaluation<double>& e,
                              const ExportRequest& req) {
  ExportMetadata m;
  m["schema_version"] = std::to_string(kControllerExportSchema);
  m["gaitopt_version"] = GAITOPT_VERSION;
  m["robot_file"] = gait.robot_path;
  m["robot_sha256"] = fileSha256(gait.robot_path);
  m["robot_name"] = gait.robot.name;
  m["gait_file"] = gait.path;
  m["gait_sha256"] = fileSha256(gait.path);
  m["steps"] = std::to_string(req.steps);
  m["rate_hz"] = formatDouble(req.rate);
  m["first_stance"] = legName(req.first_stance);
  m["step_length_m"] = formatDouble(e.motion.d);
  m["T_SS_s"] = formatDouble(e.motion.T_SS);
  m["T_DS_s"] = formatDouble(e.motion.T_DS);
  m["speed_m_per_s"] = formatDouble(e.speed);
  m["gear_ratio"] = formatDouble(gait.robot.gear_ratio);
  m["friction"] = "robot file Coulomb (smooth sign tanh(w/" +
                  formatDouble(gait.model_options.friction_smoothing) + ")) and viscous";
  m["rotor_model"] = rotorName(req.rotor);
  std::string overrides;
  for (const std::string& o : gait.overrides) overrides += (overrides.empty() ? "" : " ") + o;
  if (!overrides.empty()) m["overrides"] = overrides;
  if (req.ramp_steps > 0) {
    m["ramp_steps"] = std::to_string(req.ramp_steps);
    std::string rates;
    for (double a : req.ramp_rates)
      rates += (rates.empty() ? "" : " ") + formatDouble(a);
    m["ramp_alphad_iSS"] = rates + " (rad/s; step 0 is the standing start, DS only)";
  }
  const auto names = gait.options.parameterisation.names();
  for (std::size_t i = 0; i < names.size(); ++i)
    m["parameter." + names[i]] = formatDouble(gait.parameters(static_cast<int>(i)));
  return m;
}

std::vector<std::pair<std::string, std::string>> exportColumns() {
  std::vector<std::pair<std::string, std::string>> c = {
      {"t", "s"}, {"step", "-"}, {"phase", "-"}, {"stance", "-"}, {"event", "-"}};
  for (const NumericColumn& n : numericColumns()) c.emplace_back(n.name, n.unit);
  return c;
}

std::string exportCsv(const ExportMetadata& meta, const std::vector<ExportRow>& rows) {
  std::ostringstream out;
  for (const auto& [k, v] : meta) out << "# " << k << ": " << v << '\n';
  CsvRow units;
  CsvRow header;
  for (const auto& [name, unit] : exportColumns()) {
    header.text(name);
    units.text(unit);
  }
  out << "# units: " << units.line() << header.line();
  const std::vector<NumericColumn> cols = numericColumns();
  for (ExportRow r : rows) {
    CsvRow row;
    row.number(r.t).integer(r.step).text(phaseName(r.phase)).text(legName(r.stance))
        .integer(static_cast<int>(r.event));
    for (const NumericColumn& c : cols) row.number(c.field(r));
    out << row.line();
  }
  return out.str();
}

void writeEmbeddedText(JsonWriter& w, const std::string& key, const std::string& file,
                       const std::string& text) {
  w.key(key).beginObject();
  w.key("file").value(file);
  w.key("sha256").value(sha256Hex(text));
  w.key("yaml").value(text);
  w.endObject();
}

void writeEmbeddedFile(JsonWriter& w, const std::string& key, const std::string& path) {
  writeEmbeddedText(w, key, path, fileBytes(path));
}

namespace {

// The gait as read: the file itself, or with command-line overrides the gait file they make
// (so that a reader of the export rebuilds the gait that was exported).
void writeEmbeddedGait(JsonWriter& w, const GaitFile& gait) {
  if (gait.overrides.empty())
    writeEmbeddedFile(w, "gait", gait.path);
  else
    writeEmbeddedText(w, "gait", gait.path + " with the overrides of metadata.overrides",
                      gaitYaml(gait.robot_path, gait.parameters, gait.options, gait.model_options));
}

}  // namespace

// How the feedforward is made and recomputed at other phase rates (docs/commands/export.md).
void writeFeedforwardHead(JsonWriter& w, const Model& model) {
  w.key("feedforward").beginObject();
  w.key("rotor_model").value(model.options.rotor == RotorModel::Exact ? "exact" : "high_gear");
  w.key("equation").value("tau = B(s) sdd + C(s) sd^2 + G(s) + K + F(omega), per joint");
  w.key("B").value("coefficient of sdd (columns tau_B_*): D_Gamma25^-1 rows 2-5 of A(q) dq/ds");
  w.key("C").value("coefficient of sd^2 (columns tau_C_*): D_Gamma25^-1 rows 2-5 of "
                   "A(q) d2q/ds2 + C(q, dq/ds) dq/ds");
  w.key("G").value("gravity (columns tau_gravity_*)");
  w.key("K").value("double support only: -D_Gamma25^-1 rows 2-5 of D2^T R2 at the planned "
                   "reactions (columns tau_contact_*), which hold at the planned rates only; "
                   "0 in single support");
  w.key("F").value("friction (columns tau_friction_*): coulomb tanh(omega / smoothing) + "
                   "viscous omega, omega = dphi/ds sd the joint-side speed");
  w.key("friction").beginObject();
  w.key("joint_order").value("leg-1 order of the phase (the robot's joints 1-4)");
  w.key("coulomb").value(model.coulomb);
  w.key("viscous").value(model.viscous);
  w.key("smoothing").value(model.options.friction_smoothing);
  w.endObject();
  w.endObject();
}

void writeExportConventions(JsonWriter& w) {
  w.key("conventions").beginObject();
  w.key("frame").value("world x forward, z up, origin at the first stance foot; angles "
                       "counter-clockwise positive, in radians; SI units");
  w.key("alpha").value("angle of the leg-1 tibia from the vertical; leg 1 is the stance leg "
                       "in single support (SS), the front leg in double support (DS)");
  w.key("s").value("per phase s = (alpha - alpha_start) / (alpha_end - alpha_start): 0 at the "
                   "phase start, 1 at its end; sd = alphad / (alpha_end - alpha_start), sdd = "
                   "alphadd / (alpha_end - alpha_start)");
  w.key("physical_joints").beginArray();
  for (const char* j : kPhysicalJoints) w.value(j);
  w.endArray();
  w.key("leg1_to_physical").value(
      "a phase's joint_order (knee 1, hip 1, hip 2, knee 2) is knee_left, hip_left, hip_right, "
      "knee_right when leg 1 is the left leg (samples' stance = left), knee_right, hip_right, "
      "hip_left, knee_left when it is the right leg");
  w.key("phi").value("joint-side motor angles phi = D_Gamma^T q of q = (alpha, delta1..4): "
                     "knee 1 = delta1, hip 1 = -delta2, hip 2 = -(delta2 + delta3), knee 2 = "
                     "delta4; motor = gear_ratio phi");
  w.key("polynomials").value(
      "monomial a_k: p(s) = sum a_k s^k; bezier b_i: p(s) = sum b_i C(n,i) s^i (1-s)^(n-i); "
      "outside 0 <= s <= 1 (early or late touchdown) the same polynomials extend the path");
  w.key("tables").value("feedforward_table: values at the listed s (uniform), to be "
                        "interpolated linearly within the stated error; outside [0, 1] hold "
                        "the end values");
  w.key("events").value("event 0: sample at the fixed rate; 1: touchdown, 2: lift-off, at the "
                        "exact instant: the ending phase's row (s = 1) then the starting "
                        "phase's (s = 0)");
  w.endObject();
}

void writeCyclicGait(JsonWriter& w, const GaitEvaluation<double>& e) {
  w.key("cyclic_gait").beginObject();
  w.key("speed").value(e.speed);
  w.key("step_length").value(e.motion.d);
  w.key("t_ss").value(e.motion.T_SS);
  w.key("t_ds").value(e.motion.T_DS);
  w.endObject();
}

void writeExportPhases(JsonWriter& w, const Model& model, const GaitMotion<double>& motion) {
  w.key("phases").beginObject();
  writeSsPhase(w, model, motion);
  if (motion.T_DS > 0.0) writeDsPhase(w, model, motion);
  w.endObject();
}

std::string exportJson(const GaitFile& gait, const Model& model, const GaitEvaluation<double>& e,
                       const ExportMetadata& meta, const std::vector<ExportRow>& rows) {
  JsonWriter w;
  w.beginObject();
  // The head (everything before `phases`) is what readControllerExport parses.
  w.key("format").value("gaitopt controller export");
  w.key("schema_version").value(kControllerExportSchema);
  writeEmbeddedGait(w, gait);
  writeEmbeddedFile(w, "robot", gait.robot_path);
  writeCyclicGait(w, e);
  writeFeedforwardHead(w, model);
  writeExportConventions(w);
  w.key("metadata").beginObject();
  for (const auto& [k, v] : meta) w.key(k).value(v);
  w.endObject();
  w.key("units").beginObject();
  for (const auto& [name, unit] : exportColumns()) w.key(name).value(unit);
  w.endObject();
  writeExportPhases(w, model, e.motion);
  w.key("samples").beginObject();
  const auto column = [&](const std::string& name, const auto& get) {
    w.key(name).beginArray();
    for (const ExportRow& r : rows) w.value(get(r));
    w.endArray();
  };
  column("t", [](const ExportRow& r) { return r.t; });
  column("step", [](const ExportRow& r) { return r.step; });
  column("phase", [](const ExportRow& r) { return std::string(phaseName(r.phase)); });
  column("stance", [](const ExportRow& r) { return std::string(legName(r.stance)); });
  column("event", [](const ExportRow& r) { return static_cast<int>(r.event); });
  for (const NumericColumn& c : numericColumns())
    column(c.name, [&c](ExportRow r) { return c.field(r); });
  w.endObject();
  w.endObject();
  return w.str() + "\n";
}

ExportCsvFile readExportCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path, "", 0, "cannot read the file");
  ExportCsvFile f;
  const std::vector<NumericColumn> cols = numericColumns();
  const auto expected = exportColumns();
  std::string line;
  int line_no = 0;
  bool header_seen = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.rfind("# ", 0) == 0) {
      const std::size_t colon = line.find(": ");
      if (colon != std::string::npos) f.meta[line.substr(2, colon - 2)] = line.substr(colon + 2);
      continue;
    }
    if (!header_seen) requireCsvSchema(f.meta, path, line_no);
    const std::vector<std::string> cells = splitFields(line);
    if (cells.size() != expected.size())
      throw ConfigError(path, "", line_no,
                        "expected " + std::to_string(expected.size()) + " columns, got " +
                            std::to_string(cells.size()));
    if (!header_seen) {
      for (std::size_t i = 0; i < cells.size(); ++i)
        if (cells[i] != expected[i].first)
          throw ConfigError(path, expected[i].first, line_no, "header has '" + cells[i] + "'");
      header_seen = true;
      continue;
    }
    ExportRow r;
    r.t = parseCsvNumber(cells[0], path, "t", line_no);
    r.step = static_cast<int>(parseCsvNumber(cells[1], path, "step", line_no));
    if (cells[2] != "SS" && cells[2] != "DS")
      throw ConfigError(path, "phase", line_no, "expected SS or DS, got '" + cells[2] + "'");
    r.phase = cells[2] == "SS" ? Phase::SingleSupport : Phase::DoubleSupport;
    if (cells[3] != "left" && cells[3] != "right")
      throw ConfigError(path, "stance", line_no, "expected left or right, got '" + cells[3] + "'");
    r.stance = cells[3] == "left" ? Leg::Left : Leg::Right;
    if (cells[4] != "0" && cells[4] != "1" && cells[4] != "2")
      throw ConfigError(path, "event", line_no, "expected 0, 1 or 2, got '" + cells[4] + "'");
    r.event = static_cast<ExportEvent>(cells[4][0] - '0');
    for (std::size_t i = 0; i < cols.size(); ++i)
      cols[i].field(r) = parseCsvNumber(cells[i + 5], path, cols[i].name, line_no);
    f.rows.push_back(r);
  }
  if (!header_seen) throw ConfigError(path, "", line_no, "no header line");
  return f;
}

std::vector<double> normalisedMonomials(const LocalPolynomial<double>& p, double h) {
  std::vector<double> a(p.c.size());
  double hk = 1.0;
  for (std::size_t k = 0; k < p.c.size(); ++k, hk *= h) a[k] = p.c[k] * hk;
  return a;
}

// b_i = Σ_{k ≤ i} C(i, k)/C(n, k) a_k for the degree-n Bernstein basis.
std::vector<double> bezierFromMonomials(const std::vector<double>& a) {
  const int n = static_cast<int>(a.size()) - 1;
  const auto binom = [](int m, int k) {
    double r = 1.0;
    for (int i = 1; i <= k; ++i) r = r * (m - k + i) / i;
    return r;
  };
  std::vector<double> b(a.size(), 0.0);
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= i; ++k) b[i] += binom(i, k) / binom(n, k) * a[k];
  return b;
}

}  // namespace gaitopt
