#include "gaitopt/io/gait_file.hpp"

#include <array>
#include <cmath>
#include <regex>
#include <sstream>

#include "gaitopt/io/json_writer.hpp"
#include "gaitopt/io/robot_file.hpp"

namespace gaitopt {

namespace {

// Chebyshev grids of more than 512 intervals cost far more than they gain (the phase
// integrands are smooth) and would make the constraint vector huge.
constexpr int kMaxNodes = 512;
constexpr int kMaxCriteriaRefinement = 4;
// A step lasts about a second; 100 kHz already gives ~10^5 rows per file.
constexpr double kMaxSampleRate = 1e5;

// Documented ranges of the gait options (docs/formats/gait-file.md and docs/reliability.md): the lower
// bounds are those of the thesis' formulation, the upper ones refuse values that make every
// step undefined (a friction coefficient of 1e307) or are not physical.
namespace ranges {
const Range kFriction{0.0, 10.0, true, ""};
const Range kClearance{0.0, 1.0, false, "m"};
const Range kNormalForce{0.0, 1e4, false, "N"};
const Range kSampleRate{0.0, kMaxSampleRate, true, "Hz"};
const Range kFMin{0.0, 1e3, true, "kg m^2"};
const Range kRate{0.0, 100.0, false, "rad/s"};
const Range kNegativeRate{-100.0, 0.0, false, "rad/s"};
const Range kAngle{0.0, 1.0, false, "rad"};
// A margin on angle orderings (3.38), (3.40): a tenth of a radian is already a strong one.
const Range kAngleMargin{0.0, 0.1, false, "rad"};
const Range kReach{0.0, 1.0, false, "m^2"};
const Range kKappa{0.0, 10.0, true, ""};
const Range kSpeed{0.0, kMaxWalkingSpeed, false, "m/s"};
const Range kSmoothing{0.0, 1e3, true, "rad/s"};
const Range kFootSpeed{0.0, 10.0, false, "m/s"};
}  // namespace ranges

int integerInOr(const YamlMap& m, const std::string& key, int lo, int hi, int fallback) {
  const std::optional<double> v = m.optionalNumber(key);
  if (!v) return fallback;
  if (std::floor(*v) != *v || *v < lo || *v > hi) {
    throw m.error(key, "must be an integer from " + std::to_string(lo) + " to " +
                           std::to_string(hi) + ", got " + m.text(key));
  }
  return static_cast<int>(*v);
}

int nodesOr(const YamlMap& m, const std::string& key, int fallback) {
  return integerInOr(m, key, 2, kMaxNodes, fallback);
}

bool booleanOr(const YamlMap& m, const std::string& key, bool fallback) {
  return m.has(key) ? m.boolean(key) : fallback;
}

// A string option restricted to `choices`; returns the index of the value, or -1 if absent.
template <std::size_t N>
int choiceOr(const YamlMap& m, const std::string& key, const std::array<const char*, N>& choices) {
  return m.has(key) ? choiceIndex(m, key, choices) : -1;
}

const std::array<const char*, 2> kDsDistributions = {"torque", "energy"};
const std::array<const char*, 2> kRotorModels = {"exact", "high_gear"};
const std::array<const char*, 2> kLandings = {"zero_velocity", "impact"};
const std::array<const char*, 2> kAfterImpact = {"single_support", "double_support"};

// `landing` and `after_impact` (gait/impact_landing.hpp).
Landing parseLanding(const YamlMap& m) {
  const bool impact = choiceOr(m, "landing", kLandings) == 1;
  if (!impact) {
    if (m.has("after_impact")) throw m.error("after_impact", "needs 'landing: impact'");
    return Landing::ZeroVelocity;
  }
  return choiceOr(m, "after_impact", kAfterImpact) == 1 ? Landing::ImpactDoubleSupport
                                                        : Landing::ImpactSingleSupport;
}

// Plain YAML scalar when it is obviously safe (a path of letters, digits, '_', '-', '.',
// '/', not starting with '-'), else a double-quoted one.
std::string yamlString(const std::string& s) {
  bool plain = !s.empty() && s.front() != '-';
  for (char c : s) {
    plain = plain && ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ||
                      (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.' || c == '/');
  }
  if (plain) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

}  // namespace

Parameterisation parseParameterisation(const YamlMap& doc, Landing landing) {
  Parameterisation par;
  par.landing = landing;
  if (!doc.has("parameterisation")) return par;
  if (!doc.hasMapping("parameterisation")) {
    const std::string v = doc.string("parameterisation");
    if (v != "miossec")
      throw doc.error("parameterisation", "expected 'miossec' or a mapping {ss_points, "
                                          "ds_points}, got '" + v + "'");
    return par;
  }
  const YamlMap m = doc.map("parameterisation");
  const auto count = [&m](const char* key, int fallback) {
    const std::optional<double> v = m.optionalNumber(key);
    if (!v) return fallback;
    if (*v != std::floor(*v) || *v < 0 || *v > kMaxGaitParameters)
      throw m.error(key, "must be a whole number from 0 to " + std::to_string(kMaxGaitParameters) +
                             ", got " + m.text(key));
    return static_cast<int>(*v);
  };
  par.ss_points = count("ss_points", 1);
  par.ds_points = count("ds_points", 0);
  if (m.has("basis")) {
    const std::string basis = m.string("basis");
    if (basis != "polynomial" && basis != "bspline")
      throw m.error("basis", "expected 'polynomial' or 'bspline', got '" + basis + "'");
    par.basis = basis == "bspline" ? PathBasis::BSpline : PathBasis::Polynomial;
  }
  m.rejectUnknownKeys();
  if (par.ss_points % 2 == 0)
    throw m.error("ss_points", "must be odd (the middle point is the thesis' alpha_int), got " +
                                   std::to_string(par.ss_points));
  if (!par.hasDoubleSupport() && par.ds_points > 0)
    throw m.error("ds_points", "must be 0 with 'after_impact: single_support' (no double "
                               "support), got " + std::to_string(par.ds_points));
  if (par.size() > kMaxGaitParameters)
    throw m.error("ss_points", "gives " + std::to_string(par.size()) + " parameters, more than " +
                                   std::to_string(kMaxGaitParameters));
  return par;
}

GaitParameters parseGaitParameters(const YamlMap& m, const Parameterisation& par) {
  const std::vector<std::string> names = par.names();
  GaitParameters p(par.size());
  // Angles (α, δ, θ of the configurations, not their slopes or rates) are radians: one beyond
  // a turn is a gait file written in degrees.
  static const std::regex angle(R"((alpha|delta[0-9]|theta[0-9])_.*)");
  static const std::regex not_angle(R"(alphadot_.*|delta[0-9]s_.*)");
  for (int i = 0; i < par.size(); ++i) {
    p(i) = m.number(names[i]);
    if (std::regex_match(names[i], angle) && !std::regex_match(names[i], not_angle) &&
        std::abs(p(i)) > 2.0 * M_PI)
      throw m.error(names[i], "an angle of " + m.text(names[i]) +
                                  " rad, more than a turn: gait files hold radians (degrees?)");
  }
  // Implicit requirements of the parametrisation (digest §3.5 [G]): a forward step and a
  // double support of positive duration (the DS α(t) cubic is singular at T_DS = 0).
  for (int i : {static_cast<int>(kStepLength), static_cast<int>(kTDS)}) {
    if (!(p(i) > 0.0)) throw m.error(names[i], "must be > 0, got " + m.text(names[i]));
  }
  m.rejectUnknownKeys();
  return p;
}

GaitOptions parseGaitOptions(const YamlMap& m, ModelOptions& model_options) {
  GaitOptions o;
  o.friction_coefficient =
      numberInOr(m, "friction_coefficient", ranges::kFriction, o.friction_coefficient);
  o.clearance_height = numberInOr(m, "clearance_height", ranges::kClearance, o.clearance_height);
  o.min_normal_force = numberInOr(m, "min_normal_force", ranges::kNormalForce, o.min_normal_force);
  o.dry_friction = booleanOr(m, "dry_friction", o.dry_friction);
  if (const int k = choiceOr(m, "ds_distribution", kDsDistributions); k >= 0) {
    o.ds_distribution = k == 0 ? DsDistribution::Torque : DsDistribution::Energy;
  }
  o.sample_rate = numberInOr(m, "sample_rate", ranges::kSampleRate, o.sample_rate);
  o.ss_nodes = nodesOr(m, "ss_nodes", o.ss_nodes);
  o.ds_nodes = nodesOr(m, "ds_nodes", o.ds_nodes);
  o.criteria_refinement =
      integerInOr(m, "criteria_refinement", 1, kMaxCriteriaRefinement, o.criteria_refinement);
  if (o.ss_nodes * o.criteria_refinement > 2 * kMaxNodes) {
    throw m.error("criteria_refinement",
                  "ss_nodes * criteria_refinement must be at most " +
                      std::to_string(2 * kMaxNodes) + ", got " + std::to_string(o.ss_nodes) +
                      " * " + std::to_string(o.criteria_refinement));
  }
  o.f_min = numberInOr(m, "f_min", ranges::kFMin, o.f_min);
  o.alphadot_margin = numberInOr(m, "alphadot_margin", ranges::kRate, o.alphadot_margin);
  o.ds_alphadot_max = numberInOr(m, "ds_alphadot_max", ranges::kNegativeRate, o.ds_alphadot_max);
  if (!(o.ds_alphadot_max < 0.0)) {
    throw m.error("ds_alphadot_max", "must be < 0, got " + m.text("ds_alphadot_max"));
  }
  o.angle_margin = numberInOr(m, "angle_margin", ranges::kAngleMargin, o.angle_margin);
  o.ds_alpha_range_min =
      numberInOr(m, "ds_alpha_range_min", ranges::kAngle, o.ds_alpha_range_min);
  o.reach_margin = numberInOr(m, "reach_margin", ranges::kReach, o.reach_margin);
  o.kappa_min = numberInOr(m, "kappa_min", ranges::kKappa, o.kappa_min);
  o.joint_limit_margin = numberInOr(m, "joint_limit_margin", ranges::kAngle, o.joint_limit_margin);
  o.full_torque_envelope = booleanOr(m, "full_torque_envelope", o.full_torque_envelope);
  o.parameterisation.landing = parseLanding(m);
  o.target_speed = numberInOr(m, "target_speed", ranges::kSpeed, o.target_speed);
  o.touchdown_speed_min =
      numberInOr(m, "touchdown_speed_min", ranges::kFootSpeed, o.touchdown_speed_min);
  if (o.touchdown_speed_min > 0.0 && !o.parameterisation.landsWithImpact())
    throw m.error("touchdown_speed_min", "needs 'landing: impact' (the zero-velocity landing "
                                         "meets the ground at rest)");
  if (const int k = choiceOr(m, "rotor", kRotorModels); k >= 0) {
    model_options.rotor = k == 0 ? RotorModel::Exact : RotorModel::HighGear;
  }
  model_options.friction_smoothing =
      numberInOr(m, "friction_smoothing", ranges::kSmoothing, model_options.friction_smoothing);
  m.rejectUnknownKeys();
  return o;
}

GaitFile parseGaitDocument(const YamlMap& doc) {
  GaitFile g;
  g.path = doc.file();
  const std::string robot = doc.string("robot");
  if (robot.empty()) throw doc.error("robot", "must name the robot description file");
  g.robot_path = resolveAgainstFile(g.path, robot);  // against the gait file's directory
  if (const std::optional<YamlMap> options = doc.optionalMap("options")) {
    g.options = parseGaitOptions(*options, g.model_options);
  }
  const Parameterisation par = parseParameterisation(doc, g.options.parameterisation.landing);
  g.parameters = parseGaitParameters(doc.map("parameters"), par);
  g.options.parameterisation = par;
  doc.rejectUnknownKeys();
  return g;
}

GaitFile loadGaitFile(const std::string& path) { return loadGaitFileWithOverrides(path, {}); }

GaitFile loadGaitFileWithOverrides(const std::string& path, const std::vector<Override>& overrides) {
  GaitFile g;
  attributeOverrideErrors(path, overrides, [&] {
    const YamlMap doc(withOverrides(loadYamlFile(path), overrides), path, "");
    g = parseGaitDocument(doc);
    requireReadableFile(doc, "robot", "robot file", g.robot_path, doc.string("robot"),
                        "gait file");
  });
  g.robot = loadRobot(g.robot_path);  // errors inside the robot file name that file
  for (const Override& o : overrides) g.overrides.push_back(o.text());
  return g;
}

std::string gaitOptionsYaml(const GaitOptions& o, const ModelOptions& mo, int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  std::ostringstream out;
  const auto num = [&](const char* key, double v) {
    out << pad << key << ": " << formatDouble(v) << '\n';
  };
  const auto text = [&](const char* key, const std::string& v) {
    out << pad << key << ": " << v << '\n';
  };
  const auto flag = [&](const char* key, bool v) { text(key, v ? "true" : "false"); };
  num("friction_coefficient", o.friction_coefficient);
  num("clearance_height", o.clearance_height);
  num("min_normal_force", o.min_normal_force);
  flag("dry_friction", o.dry_friction);
  text("ds_distribution", kDsDistributions[o.ds_distribution == DsDistribution::Torque ? 0 : 1]);
  num("sample_rate", o.sample_rate);
  text("ss_nodes", std::to_string(o.ss_nodes));
  text("ds_nodes", std::to_string(o.ds_nodes));
  text("criteria_refinement", std::to_string(o.criteria_refinement));
  num("f_min", o.f_min);
  num("alphadot_margin", o.alphadot_margin);
  num("ds_alphadot_max", o.ds_alphadot_max);
  num("angle_margin", o.angle_margin);
  num("ds_alpha_range_min", o.ds_alpha_range_min);
  num("reach_margin", o.reach_margin);
  num("kappa_min", o.kappa_min);
  num("joint_limit_margin", o.joint_limit_margin);
  flag("full_torque_envelope", o.full_torque_envelope);
  num("target_speed", o.target_speed);
  if (o.parameterisation.landsWithImpact()) {
    text("landing", kLandings[1]);
    text("after_impact", kAfterImpact[o.parameterisation.hasDoubleSupport() ? 1 : 0]);
    num("touchdown_speed_min", o.touchdown_speed_min);
  }
  text("rotor", kRotorModels[mo.rotor == RotorModel::Exact ? 0 : 1]);
  num("friction_smoothing", mo.friction_smoothing);
  return out.str();
}

std::string gaitYaml(const std::string& robot_path_relative, const GaitParameters& p,
                     const GaitOptions& options, const ModelOptions& model_options) {
  std::ostringstream out;
  const Parameterisation& par = options.parameterisation;
  out << "# Gait file written by gaitopt: one walking step of Miossec's polynomial\n"
         "# parametrisation (radians, metres, seconds) and the options it was evaluated with.\n"
         "# Values are at full precision so that reading the file back is exact.\n";
  out << "robot: " << yamlString(robot_path_relative) << "  # relative to this file\n";
  if (!par.isThesis())
    out << "parameterisation: {ss_points: " << par.ss_points << ", ds_points: " << par.ds_points
        << (par.basis == PathBasis::BSpline ? ", basis: bspline" : "") << "}\n";
  out << "parameters:\n";
  const std::vector<std::string> names = par.names();
  for (int i = 0; i < par.size(); ++i) out << "  " << names[i] << ": " << formatDouble(p(i)) << '\n';
  out << "options:\n" << gaitOptionsYaml(options, model_options, 2);
  return out.str();
}

}  // namespace gaitopt
