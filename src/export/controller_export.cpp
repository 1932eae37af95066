#include "gaitopt/export/controller_export.hpp"

#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/file_digest.hpp"
#include "gaitopt/io/json_writer.hpp"
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

Leg otherLeg(Leg l) { return l == Leg::Left ? Leg::Right : Leg::Left; }

const char* legName(Leg l) { return l == Leg::Left ? "left" : "right"; }
const char* phaseName(Phase p) { return p == Phase::SingleSupport ? "SS" : "DS"; }

// Numeric columns after t, step, phase, stance: name, unit and the field they read/write.
struct NumericColumn {
  std::string name, unit;
  std::function<double&(ExportRow&)> field;
};

std::vector<NumericColumn> numericColumns() {
  std::vector<NumericColumn> c = {
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
      {"tau_friction", "N*m", &ExportRow::tau_friction}};
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

void writeSsPhase(JsonWriter& w, const GaitMotion<double>& mo) {
  const double h = mo.alpha_fSS - mo.alpha_iSS;
  w.key("SS").beginObject();
  w.key("phase_variable").value("s = (alpha - alpha_start) / (alpha_end - alpha_start), 0 at "
                                "lift-off, 1 at touchdown");
  w.key("alpha_start").value(mo.alpha_iSS);
  w.key("alpha_end").value(mo.alpha_fSS);
  w.key("duration").value(mo.T_SS);
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
  w.endObject();
}

void writeDsPhase(JsonWriter& w, const GaitMotion<double>& mo) {
  const double alpha_i = mo.ds_alpha.c[0];
  const double alpha_f = mo.ds_alpha(mo.T_DS).value;
  w.key("DS").beginObject();
  w.key("time_variable").value("tau = t / duration, t from touchdown");
  w.key("phase_variable").value("s = (alpha - alpha_start) / (alpha_end - alpha_start)");
  w.key("duration").value(mo.T_DS);
  w.key("alpha_start").value(alpha_i);
  w.key("alpha_end").value(alpha_f);
  writePolynomial(w, "alpha_of_tau", normalisedMonomials(mo.ds_alpha, mo.T_DS));
  w.key("outputs").beginObject();
  LocalPolynomial<double> hip = mo.ds_delta2.polynomial();
  for (double& c : hip.c) c = -c;
  writePolynomial(w, "phi_knee_front", normalisedMonomials(mo.ds_delta1.polynomial(), alpha_f - alpha_i));
  writePolynomial(w, "phi_hip_front", normalisedMonomials(hip, alpha_f - alpha_i));
  w.endObject();
  w.key("closed_chain").value("phi_hip_rear and phi_knee_rear follow from the rear leg's "
                              "inverse kinematics with the rear foot at (-step_length, 0) "
                              "from the front foot, knee bent forward (3.18)-(3.19)");
  w.endObject();
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

std::vector<ExportRow> exportWalk(const Model& model, const std::vector<PlannedSample>& samples,
                                  Leg first_stance) {
  std::vector<ExportRow> rows;
  rows.reserve(samples.size());
  for (const PlannedSample& s : samples)
    rows.push_back(exportRow(model, s.row, s.step,
                             s.leg1_is_first_stance ? first_stance : otherLeg(first_stance),
                             s.foot1_x, s.t));
  return rows;
}

std::vector<ExportRow> exportTrajectory(const GaitEvaluator& ev, const GaitEvaluation<double>& e,
                                        const Model& model, const ExportRequest& req) {
  if (req.steps < 1 || !(req.rate > 0.0))
    throw std::invalid_argument("exportTrajectory: steps must be >= 1 and rate > 0");
  const auto step = std::make_shared<const GaitEvaluation<double>>(e);
  const std::vector<WalkStepMotion> walk(req.steps, WalkStepMotion{step, true});
  return exportWalk(model, sampleWalk(ev, walk, req.rate), req.first_stance);
}

ExportMetadata exportMetadata(const GaitFile& gait, const GaitEvaluation<double>& e,
                              const ExportRequest& req) {
  ExportMetadata m;
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
      {"t", "s"}, {"step", "-"}, {"phase", "-"}, {"stance", "-"}};
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
    row.number(r.t).integer(r.step).text(phaseName(r.phase)).text(legName(r.stance));
    for (const NumericColumn& c : cols) row.number(c.field(r));
    out << row.line();
  }
  return out.str();
}

std::string exportJson(const ExportMetadata& meta, const std::vector<ExportRow>& rows,
                       const GaitEvaluation<double>& e) {
  JsonWriter w;
  w.beginObject();
  w.key("format").value("gaitopt controller export 1");
  w.key("metadata").beginObject();
  for (const auto& [k, v] : meta) w.key(k).value(v);
  w.endObject();
  w.key("units").beginObject();
  for (const auto& [name, unit] : exportColumns()) w.key(name).value(unit);
  w.endObject();
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
  for (const NumericColumn& c : numericColumns())
    column(c.name, [&c](ExportRow r) { return c.field(r); });
  w.endObject();
  w.key("phases").beginObject();
  writeSsPhase(w, e.motion);
  writeDsPhase(w, e.motion);
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
    for (std::size_t i = 0; i < cols.size(); ++i)
      cols[i].field(r) = parseCsvNumber(cells[i + 4], path, cols[i].name, line_no);
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
