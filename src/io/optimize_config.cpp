#include "gaitopt/io/optimize_config.hpp"

#include "gaitopt/gait/richer_parameterisation.hpp"

#include <array>
#include <cmath>
#include <filesystem>

#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/opt/initial_guess.hpp"
#include "gaitopt/opt/nlp_solver.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "gaitopt/io/yaml_reader.hpp"

namespace gaitopt {

namespace {

// A string restricted to `choices`: the index of the value, or `fallback` when absent.
template <std::size_t N>
int choice(const YamlMap& m, const std::string& key, const std::array<const char*, N>& choices,
           int fallback) {
  if (!m.has(key)) {
    m.optionalNumber(key);  // absent: only records the key as known
    return fallback;
  }
  return choiceIndex(m, key, choices);
}

// An integer >= minimum, or `fallback` when absent.
int integerOr(const YamlMap& m, const std::string& key, int minimum, int fallback) {
  const std::optional<double> v = m.optionalNumber(key);
  if (!v) return fallback;
  if (std::floor(*v) != *v || *v < minimum || *v > 1e9) {
    throw m.error(key, "must be an integer >= " + std::to_string(minimum) + " and <= 1e9, got " +
                           m.text(key));
  }
  return static_cast<int>(*v);
}

// Same order as the enums.
const std::array<const char*, 3> kCriteria = {"C_Gamma", "C_E", "W"};
const std::array<const char*, 3> kBackends = {"nlopt_slsqp", "ipopt", "nlopt_cobyla"};
const std::array<const char*, 2> kHierarchies = {"staged", "direct"};
const std::array<const char*, 2> kGradientModes = {"exact", "finite_difference"};
const std::array<const char*, 5> kHessians = {"limited_memory", "bfgs", "exact", "exact_unmodified",
                                              "gauss_newton"};

bool isPlainFileName(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.size() <= 255 &&
         name.find('/') == std::string::npos && printable(name) == name;
}

// A referenced file must exist and be readable; otherwise the error is at the config's key.
void requireReadable(const YamlMap& doc, const std::string& key, const std::string& what,
                     const std::string& resolved, const std::string& given) {
  requireReadableFile(doc, key, what, resolved, given, "configuration file");
}

// One Ipopt option, checked against Ipopt's own registered options (unknown key, wrong type,
// value out of its range or list). Options naming files are confined to the run's output
// directory: output_file must be a plain file name (placed in --out at run time, see
// placeIpoptOutputFile) and option_file_name is refused. A linear solver must be loadable.
void checkIpoptOption(const YamlMap& ipopt, const std::pair<std::string, std::string>& option) {
  const auto& [key, value] = option;
  if (key == "option_file_name") {
    throw ipopt.error(key, "not allowed: put the Ipopt options in this file instead");
  }
  if (key == "output_file" && !isPlainFileName(value)) {
    throw ipopt.error(key, "must be a plain file name (it is written inside --out), got '" +
                               printable(value) + "'");
  }
  if (!rejectedIpoptOption({option}).empty()) {
    throw ipopt.error(key, "Ipopt rejects this option or its value '" + printable(value) +
                               "' (see the Ipopt options reference)");
  }
  if (key == "linear_solver" && !ipoptLinearSolverAvailable(value)) {
    throw ipopt.error(key, "linear solver '" + printable(value) +
                               "' is not available in this Ipopt build (e.g. the HSL solvers "
                               "need libhsl); the default is mumps");
  }
}

SolverSettings parseSolver(const YamlMap& m) {
  SolverSettings s;
  switch (choice(m, "backend", kBackends, 0)) {
    case 1: s.backend = Backend::Ipopt; break;
    case 2: s.backend = Backend::NloptCobyla; break;
    default: s.backend = Backend::NloptSlsqp; break;
  }
  s.hierarchy = choice(m, "hierarchy", kHierarchies, 0) == 1 ? HierarchyStrategy::Direct
                                                              : HierarchyStrategy::Staged;
  s.max_iter = integerOr(m, "max_iter", 1, s.max_iter);
  if (const std::optional<double> tol = m.optionalNumber("tol")) {
    if (!(*tol > 0.0) || *tol > 1.0) {
      throw m.error("tol", "must be > 0 and <= 1, got " + m.text("tol"));
    }
    s.tol = *tol;
  }
  if (m.has("constraint_exchange")) s.constraint_exchange = m.boolean("constraint_exchange");
  s.gradients = choice(m, "gradients", kGradientModes, 0) == 1 ? GradientMode::FiniteDifference
                                                               : GradientMode::Exact;
  s.print_every = integerOr(m, "print_every", 0, s.print_every);
  if (m.has("hessian")) {
    if (s.backend != Backend::Ipopt)
      throw m.error("hessian", "is used only with backend: ipopt; remove it or change the backend");
    s.hessian = static_cast<HessianMode>(choice(m, "hessian", kHessians, 0));
  }
  if (const std::optional<YamlMap> ipopt = m.optionalMap("ipopt")) {
    if (s.backend != Backend::Ipopt) {
      throw m.error("ipopt", std::string("Ipopt options are used only with backend: ipopt (this "
                                         "run uses ") +
                                 backendName(s.backend) + "); remove them or change the backend");
    }
    s.ipopt_options = ipopt->scalarEntries();
    for (const auto& option : s.ipopt_options) checkIpoptOption(*ipopt, option);
  }
  return s;
}

}  // namespace

namespace {

OptimizeConfig parseOptimizeConfig(const std::string& path, const YamlMap& doc) {
  OptimizeConfig c;
  c.path = path;

  const std::string robot = doc.string("robot");
  if (robot.empty()) throw doc.error("robot", "must name the robot description file");
  c.robot_path = resolveAgainstFile(path, robot);

  if (const std::optional<YamlMap> options = doc.optionalMap("options")) {
    if (options->has("target_speed")) {
      throw options->error("target_speed",
                           "not allowed here: the optimiser's target is the top-level 'speed'");
    }
    c.options = parseGaitOptions(*options, c.model_options);
  }

  switch (choice(doc, "criterion", kCriteria, 0)) {
    case 1: c.criterion = Criterion::Energy; break;
    case 2: c.criterion = Criterion::Work; break;
    default: c.criterion = Criterion::Torque; break;
  }

  if (const std::optional<double> speed = doc.optionalNumber("speed")) {
    if (!(*speed > 0.0) || *speed > kMaxWalkingSpeed) {
      throw doc.error("speed", "must be > 0 and <= " + showNumber(kMaxWalkingSpeed) +
                                   " m/s (leave it out for a free speed), got " +
                                   doc.text("speed"));
    }
    c.speed = *speed;
  }
  c.options.target_speed = c.speed.value_or(0.0);

  c.options.parameterisation = parseParameterisation(doc, c.options.parameterisation.landing);
  c.parameterisation = c.options.parameterisation.label();

  std::string initial = "default";
  if (doc.has("initial_guess")) {
    initial = doc.string("initial_guess");
    if (initial.empty()) {
      throw doc.error("initial_guess", "expected 'default' or a gait file, got an empty string");
    }
  } else {
    doc.optionalNumber("initial_guess");
  }

  if (const std::optional<YamlMap> solver = doc.optionalMap("solver")) {
    c.solver = parseSolver(*solver);
  }
  doc.rejectUnknownKeys();

  requireReadable(doc, "robot", "robot file", c.robot_path, robot);
  c.robot = loadRobot(c.robot_path);  // errors inside the robot file name that file

  if (initial != "default") {
    const std::string gait = resolveAgainstFile(path, initial);
    requireReadable(doc, "initial_guess", "gait file", gait, initial);
    c.initial_guess_path = gait;
    const GaitFile guess = loadGaitFile(gait);  // errors name the gait file
    c.initial_guess_parameters = guess.parameters;
    c.initial_guess_parameterisation = guess.options.parameterisation;
    if (guess.options.parameterisation.ss_points > c.options.parameterisation.ss_points ||
        guess.options.parameterisation.ds_points > c.options.parameterisation.ds_points ||
        (guess.options.parameterisation.landsWithImpact() &&
         !c.options.parameterisation.landsWithImpact()))
      throw doc.error("initial_guess", "the gait file's parameterisation (" +
                                           guess.options.parameterisation.label() +
                                           ") is richer than the configured one (" +
                                           c.parameterisation + ")");
  }
  return c;
}

}  // namespace

OptimizeConfig loadOptimizeConfig(const std::string& path) {
  return loadOptimizeConfigWithOverrides(path, {});
}

OptimizeConfig loadOptimizeConfigWithOverrides(const std::string& path,
                                               const std::vector<Override>& overrides) {
  OptimizeConfig c;
  attributeOverrideErrors(path, overrides, [&] {
    c = parseOptimizeConfig(path, YamlMap(withOverrides(loadYamlFile(path), overrides), path, ""));
  });
  for (const Override& o : overrides) c.overrides.push_back(o.text());
  return c;
}

void placeIpoptOutputFile(SolverSettings& solver, const std::string& dir) {
  for (auto& [key, value] : solver.ipopt_options) {
    if (key == "output_file") value = (std::filesystem::path(dir) / value).string();
  }
}

GaitParameters configuredInitialGuess(const OptimizeConfig& config, const Model& model) {
  const GaitParameters p = config.initial_guess_path ? config.initial_guess_parameters
                                                     : defaultInitialGuess(model, config.speed);
  const Parameterisation from =
      config.initial_guess_path ? config.initial_guess_parameterisation : Parameterisation{};
  if (from == config.options.parameterisation) return p;
  // A coarser start is written in the configured parameterisation without changing its motion.
  GaitOptions coarse = config.options;
  coarse.parameterisation = from;
  if (!from.landsWithImpact()) coarse.touchdown_speed_min = 0.0;  // it lands at rest
  return toRicherParameterisation(GaitEvaluator(config.robot, coarse, config.model_options), p,
                          config.options.parameterisation);
}

OptimizationRequest optimizationRequest(const OptimizeConfig& config,
                                        const GaitParameters& initial) {
  OptimizationRequest r;
  r.criterion = config.criterion;
  r.speed = config.speed;
  r.initial = initial;
  r.solver = config.solver;
  return r;
}

}  // namespace gaitopt
