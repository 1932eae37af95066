// `import gaitopt`: pybind11 bindings of libgaitopt's types. A robot and a gait are read by the
// library's readers, a GaitEvaluator evaluates parameter vectors into evaluation objects whose
// numbers are the library's (criteria, timing, constraint vector, feasibility verdict) and
// whose trajectory is the library's sampler's, as NumPy arrays; optimisation and diagnosis
// return the library's results as Python objects. File errors raise gaitopt.ConfigError with
// the reader's message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/gait/constraint_summary.hpp"
#include "gaitopt/gait/feasibility.hpp"
#include "gaitopt/io/summary_file.hpp"
#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/ident/diagnose.hpp"
#include "gaitopt/io/diagnosis_file.hpp"
#include "gaitopt/impact/solve_impact.hpp"
#include "gaitopt/io/output_transaction.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/impact_report.hpp"
#include "gaitopt/io/measured_data.hpp"
#include "gaitopt/io/model_report.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/io/optimize_output.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/opt/optimizer.hpp"
#include "gaitopt_version.hpp"

namespace py = pybind11;

namespace gaitopt {
namespace {

py::object fromJson(const std::string& json) {
  return py::module_::import("json").attr("loads")(json);
}

Vec5 toVec5(const std::vector<double>& v, const char* name) {
  if (v.size() != 5) throw py::value_error(std::string(name) + ": 5 values expected");
  return Eigen::Map<const Vec5>(v.data());
}

template <class Vector> py::array_t<double> vectorArray(const Vector& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  for (py::ssize_t i = 0; i < a.size(); ++i) a.mutable_at(i) = v[i];
  return a;
}

// Rows × N of fixed-size vectors taken from each trajectory row by `get`.
template <int N, class Rows, class Get> py::array_t<double> rowsArray(const Rows& rows, Get get) {
  py::array_t<double> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(N)});
  auto m = a.template mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < m.shape(0); ++i) {
    const auto v = get(rows[i]);
    for (int j = 0; j < N; ++j) m(i, j) = v(j);
  }
  return a;
}

template <class T> py::object noneUnless(bool present, const T& value) {
  return present ? py::cast(value) : py::object(py::none());
}

// A robot file read by loadRobot and its model (buildModel), or a robot the library made
// (a gait file's, a diagnosis' extended robot).
class Robot {
 public:
  Robot(const RobotParams& params, const ModelOptions& options)
      : model_(buildModel(params, options)) {}
  Robot(const std::string& path, const std::string& rotor)
      : Robot(loadRobot(path), modelOptions(rotor)) {}

  const Model& model() const { return model_; }
  const RobotParams& params() const { return model_.robot; }
  // The document of `gaitopt model --q ... [--qd ...] [--qdd ...]`.
  py::object modelReport(const std::vector<double>& q,
                         const std::optional<std::vector<double>>& qd,
                         const std::optional<std::vector<double>>& qdd) const {
    std::optional<Vec5> acc;
    if (qdd) acc = toVec5(*qdd, "qdd");
    return fromJson(modelReportJson(model_, toVec5(q, "q"),
                                    qd ? toVec5(*qd, "qd") : Vec5(Vec5::Zero()), acc));
  }
  // The document of `gaitopt impact --q ... --qd ... --mu MU --model MODEL` (its input checks:
  // foot 2 on the ground, arriving downward).
  py::object impact(const std::vector<double>& q_list, const std::vector<double>& qd_list,
                    double mu, const std::string& kind) const {
    if (kind != "algebraic" && kind != "differential")
      throw py::value_error("model: 'algebraic' or 'differential' expected, got '" + kind + "'");
    if (!(mu >= 0.0) || !std::isfinite(mu)) throw py::value_error("mu: a finite value >= 0 expected");
    const Vec5 q = toVec5(q_list, "q"), qd = toVec5(qd_list, "qd");
    const PinnedTerms<double> t = pinnedTerms(model_, q, qd);
    if (std::abs(t.foot2(1)) > 1e-9)
      throw py::value_error("q: foot 2 height z2 = " + std::to_string(t.foot2(1)) +
                            " m; an impact needs foot 2 on the ground (|z2| <= 1e-9 m)");
    if (!(t.D2.row(1).dot(qd) < 0.0))
      throw py::value_error("qd: foot 2 must arrive with V2z < 0");
    ImpactOptions options;
    options.mu = mu;
    const ImpactResult r = solveImpactFromPinned(
        model_, q, qd, kind == "algebraic" ? ImpactModelKind::Algebraic : ImpactModelKind::Differential,
        options);
    JsonWriter w;
    w.beginObject();
    writeImpactResultFields(w, r);
    w.endObject();
    return fromJson(w.str());
  }

 private:
  static ModelOptions modelOptions(const std::string& rotor) {
    if (rotor != "exact" && rotor != "high_gear")
      throw py::value_error("rotor: 'exact' or 'high_gear' expected, got '" + rotor + "'");
    ModelOptions options;
    options.rotor = rotor == "exact" ? RotorModel::Exact : RotorModel::HighGear;
    return options;
  }
  Model model_;
};

std::vector<std::string> parameterNames(const GaitOptions& options) {
  return options.parameterisation.names();
}

// A gait file read by loadGaitFile.
struct Gait {
  GaitFile file;
  explicit Gait(const std::string& path) : file(loadGaitFile(path)) {}
  Robot robot() const { return Robot(file.robot, file.model_options); }
};

// One step sampled by sampleTrajectory: one row per sample, vectors as rows × components.
struct Trajectory {
  py::object t, phase, q, qd, qdd, torques, reactions, foot2, com, knee1, hip, knee2, head,
      omega, gamma_max, sigma, clearance;

  explicit Trajectory(const std::vector<TrajectoryRow>& rows) {
    std::vector<double> times, sigmas, clearances;
    std::vector<std::string> phases;
    for (const TrajectoryRow& r : rows) {
      times.push_back(r.t);
      sigmas.push_back(r.sigma);
      clearances.push_back(r.clearance);
      phases.push_back(r.phase == Phase::SingleSupport ? "SS" : "DS");
    }
    t = vectorArray(times);
    sigma = vectorArray(sigmas);
    clearance = vectorArray(clearances);
    phase = py::module_::import("numpy").attr("array")(phases);
    q = rowsArray<5>(rows, [](const TrajectoryRow& r) { return r.q; });
    qd = rowsArray<5>(rows, [](const TrajectoryRow& r) { return r.qd; });
    qdd = rowsArray<5>(rows, [](const TrajectoryRow& r) { return r.qdd; });
    torques = rowsArray<4>(rows, [](const TrajectoryRow& r) { return r.gamma_star; });
    reactions = rowsArray<4>(rows, [](const TrajectoryRow& r) {
      return Vec4(r.R1(0), r.R1(1), r.R2(0), r.R2(1));
    });
    foot2 = rowsArray<2>(rows, [](const TrajectoryRow& r) { return r.foot2; });
    com = rowsArray<2>(rows, [](const TrajectoryRow& r) { return r.com; });
    knee1 = rowsArray<2>(rows, [](const TrajectoryRow& r) { return r.knee1; });
    hip = rowsArray<2>(rows, [](const TrajectoryRow& r) { return r.hip; });
    knee2 = rowsArray<2>(rows, [](const TrajectoryRow& r) { return r.knee2; });
    head = rowsArray<2>(rows, [](const TrajectoryRow& r) { return r.head; });
    omega = rowsArray<4>(rows, [](const TrajectoryRow& r) { return r.omega; });
    gamma_max = rowsArray<4>(rows, [](const TrajectoryRow& r) { return r.gamma_max; });
  }
};

// One evaluated parameter vector, with the evaluator that made it (the trajectory is sampled
// from both).
struct Evaluation {
  std::shared_ptr<const GaitEvaluator> evaluator;
  GaitParameters parameters;
  GaitEvaluation<double> value;
  FeasibilityVerdict verdict;

  Evaluation(std::shared_ptr<const GaitEvaluator> ev, const GaitParameters& p,
             const GaitEvaluation<double>& e)
      : evaluator(std::move(ev)), parameters(p), value(e),
        verdict(feasibilityVerdict(*evaluator, p, e)) {}

  // Criteria exist for a defined step whose motion was computed; T_SS and the speed once the
  // zero dynamics ran (as in summary.json).
  bool hasCriteria() const { return value.motion_computed && value.defined(); }
  bool hasTiming() const { return zeroDynamicsComputed(*evaluator, value); }

  py::list constraints() const {
    py::list groups;
    const ConstraintLayout& layout = evaluator->layout();
    for (int id = 0; id < static_cast<int>(layout.groups().size()); ++id) {
      const ConstraintGroup& g = layout[id];
      if (g.count == 0) continue;
      const ConstraintGroupSummary s = summarizeConstraintGroup(g, value);
      py::dict d;
      d["name"] = g.name;
      d["level"] = g.level;
      d["equation"] = g.equation;
      d["unit"] = g.unit;
      d["offset"] = g.offset;
      d["count"] = g.count;
      d["values"] = vectorArray(std::vector<double>(value.g.begin() + g.offset,
                                                    value.g.begin() + g.offset + g.count));
      d["defined"] = s.defined;
      d["value"] = noneUnless(s.defined > 0 && std::isfinite(s.value), s.value);
      groups.append(d);
    }
    return groups;
  }
  py::array_t<int> levels() const {
    py::array_t<int> a(static_cast<py::ssize_t>(value.g.size()));
    for (py::ssize_t k = 0; k < a.size(); ++k)
      a.mutable_at(k) = evaluator->layout().levelOf(static_cast<int>(k));
    return a;
  }
  py::object trajectory(std::optional<double> sample_rate) const {
    if (!hasCriteria()) return py::none();
    const double rate = sample_rate.value_or(evaluator->options().sample_rate);
    if (!(rate > 0.0)) throw py::value_error("sample_rate: a value > 0 expected");
    return py::cast(Trajectory(sampleTrajectory(*evaluator, value, rate)));
  }
};

GaitParameters toParameters(const GaitEvaluator& ev, const py::array_t<double>& p) {
  if (p.ndim() != 1 || p.size() != ev.numParameters())
    throw py::value_error("parameters: " + std::to_string(ev.numParameters()) +
                          " values expected, got " + std::to_string(p.size()));
  GaitParameters out(p.size());
  for (py::ssize_t i = 0; i < p.size(); ++i) out(i) = p.at(i);
  return out;
}

// A GaitEvaluator of a gait file's robot and options, evaluating any parameter vector.
struct Evaluator {
  std::shared_ptr<const GaitEvaluator> evaluator;
  GaitParameters gait_parameters;

  explicit Evaluator(const Gait& gait)
      : evaluator(std::make_shared<const GaitEvaluator>(gait.file.robot, gait.file.options,
                                                        gait.file.model_options)),
        gait_parameters(gait.file.parameters) {}

  Evaluation evaluate(const std::optional<py::array_t<double>>& p) const {
    const GaitParameters params = p ? toParameters(*evaluator, *p) : gait_parameters;
    py::gil_scoped_release release;
    return Evaluation(evaluator, params, evaluator->evaluate(params));
  }
};

struct Optimization {
  OptimizationResult result;
  Evaluation evaluation;
  std::string gait_yaml;
};

// As `gaitopt optimize --config FILE --quiet [--out DIR]`; the files are written only when
// `out` is given.
Optimization optimize(const std::string& config_path, const std::optional<std::string>& out) {
  const OptimizeConfig config = loadOptimizeConfig(config_path);
  py::gil_scoped_release release;  // a long run should not block other Python threads
  // As the CLI: `out` checked before the work, its files published by one rename.
  OutputTransaction output({{"config", config_path}});
  const std::string dir =
      out ? output.directory("out", *out,
                             std::vector<std::string>{"summary.json", "gait.yaml", "trajectory.csv"}) : "";
  const auto evaluator =
      std::make_shared<const GaitEvaluator>(config.robot, config.options, config.model_options);
  const GaitParameters initial = configuredInitialGuess(config, evaluator->model());
  OptimizationResult r = optimizeGait(*evaluator, optimizationRequest(config, initial), nullptr);
  const OptimizationOutputs outputs = optimizationOutputs(*evaluator, config, r, out.value_or("."));
  if (out) {
    writeOptimizationOutputs(dir, outputs);
    output.commit();
  }
  Evaluation evaluation(evaluator, r.parameters, r.evaluation);
  return Optimization{std::move(r), std::move(evaluation), outputs.gait_yaml};
}

// As `gaitopt export --gait FILE --format json`: the JSON document as a dict with each
// `samples` column a numpy array; with `out`, the file is written as by the CLI (csv or json by
// `format`). An undefined step raises ValueError naming the gait file.
py::dict exportGait(const std::string& gait_path, int steps, double rate,
                    const std::string& first_stance, const std::string& format,
                    const std::optional<std::string>& out) {
  if (steps < 1 || !(rate > 0.0) || rate > 1e5)
    throw py::value_error("export: steps >= 1 and 0 < rate <= 1e5 expected");
  if (first_stance != "left" && first_stance != "right")
    throw py::value_error("first_stance: 'left' or 'right' expected, got '" + first_stance + "'");
  if (format != "csv" && format != "json")
    throw py::value_error("format: 'csv' or 'json' expected, got '" + format + "'");
  const GaitFile gait = loadGaitFile(gait_path);
  std::string json;
  {
    py::gil_scoped_release release;
    const GaitEvaluator evaluator(gait.robot, gait.options, gait.model_options);
    const GaitEvaluation<double> e = evaluator.evaluate(gait.parameters);
    if (!e.defined() || !e.motion_computed)
      throw py::value_error(gait_path + ": the step is undefined (failed level " +
                            std::to_string(e.failed_level) + "); nothing exported");
    ExportRequest req;
    req.steps = steps;
    req.rate = rate;
    req.first_stance = first_stance == "left" ? Leg::Left : Leg::Right;
    const Model model = buildModel(gait.robot, gait.model_options);  // the file's full friction
    const std::vector<ExportRow> rows = exportTrajectory(evaluator, e, model, req);
    const ExportMetadata meta = exportMetadata(gait, e, req);
    json = exportJson(gait, model, e, meta, rows);
    if (out) writeFileAtomically(*out, format == "csv" ? exportCsv(meta, rows) : json);
  }
  py::dict result = fromJson(json);
  const py::object array = py::module_::import("numpy").attr("array");
  py::dict samples = result["samples"];
  for (auto item : samples) samples[item.first] = array(item.second);
  return result;
}

py::dict channelValues(const std::array<double, kNumChannels>& values) {
  py::dict d;
  for (int c = 0; c < kNumChannels; ++c) d[kChannelNames[c]] = values[c];
  return d;
}

py::dict channelReport(const ChannelReport& r) {
  py::dict d;
  d["rms"] = channelValues(r.rms);
  d["rms_ss"] = channelValues(r.rms_ss);
  d["rms_ds"] = channelValues(r.rms_ds);
  d["relative_rms"] = channelValues(r.relative_rms);
  d["simulation_error"] = vectorArray(r.simulation_error);
  d["normalised_rms"] = r.normalised_rms;
  return d;
}

py::dict effectDict(const Effect& e) {
  py::dict d;
  d["effect"] = effectInfo(e.kind).name;
  d["joint"] = jointName(e.joint);
  d["value"] = e.value;
  return d;
}

py::array_t<bool> rowMask(const std::vector<char>& rows) {
  py::array_t<bool> a(static_cast<py::ssize_t>(rows.size()));
  for (py::ssize_t i = 0; i < a.size(); ++i) a.mutable_at(i) = rows[i] != 0;
  return a;
}

py::array_t<double> residualArray(const ResidualMatrix& r) {
  py::array_t<double> a({static_cast<py::ssize_t>(r.rows()), static_cast<py::ssize_t>(r.cols())});
  auto m = a.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < m.shape(0); ++i)
    for (py::ssize_t j = 0; j < m.shape(1); ++j) m(i, j) = r(i, j);
  return a;
}

// The fields of a Diagnosis as Python objects.
py::dict diagnosisDict(const Diagnosis& d, const ModelOptions& model_options) {
  py::dict r;
  r["holdout_rows"] = rowMask(d.holdout_rows);
  r["fit_rows"] = rowMask(d.fit_rows);
  r["nominal_all"] = channelReport(d.nominal_all);
  r["nominal"] = channelReport(d.nominal);
  r["extended"] = channelReport(d.extended);
  py::list candidates, causes;
  for (const CandidateResult& c : d.candidates) {
    py::dict e = effectDict(c.effect);
    e["stderr"] = c.stderr_;
    e["rss"] = c.rss;
    e["bic"] = c.bic;
    e["holdout_rms"] = c.holdout_rms;
    e["p_value"] = c.p_value;
    candidates.append(e);
  }
  for (const Cause& c : d.causes) {
    py::dict e = effectDict(c.effect);
    e["stderr"] = c.stderr_;
    e["p_value"] = c.p_value;
    e["confounded_with"] = c.confounded_with;
    causes.append(e);
  }
  r["candidates"] = candidates;
  r["causes"] = causes;
  r["extended_robot"] = Robot(d.extended_robot, model_options);
  r["channels"] = std::vector<std::string>(kChannelNames.begin(), kChannelNames.end());
  r["nominal_residuals"] = residualArray(d.nominal_residuals);
  r["extended_residuals"] = residualArray(d.extended_residuals);
  r["rms_reduction_pct"] = channelValues(d.rms_reduction_pct);
  r["overall_pct"] = d.overall_pct;
  r["simulation_error_reduction_pct"] = d.simulation_error_reduction_pct;
  r["smoothing"] = d.smoothing;
  py::dict inertial;
  inertial["tried"] = d.inertial.tried;
  inertial["accepted"] = d.inertial.accepted;
  inertial["nominal"] = vectorArray(d.inertial.nominal);
  inertial["fitted"] = vectorArray(d.inertial.fitted);
  inertial["p_value"] = d.inertial.p_value;
  inertial["active"] = d.inertial.active;
  r["inertial"] = inertial;
  std::vector<std::string> effect_channels;
  for (int c : d.effect_channels) effect_channels.push_back(kChannelNames[c]);
  r["effect_channels"] = effect_channels;
  r["effect_channels_pct"] = d.effect_channels_pct;
  return r;
}

// As `gaitopt diagnose --robot R --data D [--holdout K] [--out DIR]`: the diagnosis' fields
// plus "report" (report.md), "residuals_csv" and "extended_robot_yaml" (texts); the four
// files are written into `out` when given.
py::dict diagnoseData(const std::string& robot_path, const std::string& data_path, int holdout,
                      const std::optional<std::string>& out) {
  const RobotParams robot = loadRobot(robot_path);
  const MeasuredData data = readMeasuredCsv(data_path);
  DiagnoseOptions options;
  options.holdout = holdout;
  Diagnosis d;
  DiagnosisDocuments documents;
  {
    py::gil_scoped_release release;
    // As the CLI: `out` checked before the work, its four files published by one rename.
    OutputTransaction output({{"robot", robot_path}, {"data", data_path}});
    const std::string dir = out ? output.directory("out", *out, diagnosisFileNames()) : "";
    try {
      d = diagnose(robot, ModelOptions{}, data, options);
    } catch (const std::invalid_argument& e) {
      throw py::value_error(std::string("holdout: ") + e.what());
    }
    documents = diagnosisDocuments(robot_path, data, d);
    if (out) {
      writeDiagnosisFiles(dir, documents);
      output.commit();
    }
  }
  py::dict result = diagnosisDict(d, ModelOptions{});
  result["report"] = documents.report;
  result["residuals_csv"] = documents.residuals_csv;
  result["extended_robot_yaml"] = documents.extended_robot_yaml;
  return result;
}

void bindRobot(py::module_& m) {
  py::class_<Robot>(m, "Robot", "A robot description file read by the library (loadRobot + buildModel)")
      .def(py::init<const std::string&, const std::string&>(), py::arg("path"),
           py::arg("rotor") = "exact")
      .def_property_readonly("name", [](const Robot& r) { return r.params().name; })
      .def_property_readonly("source_file", [](const Robot& r) { return r.params().source_file; })
      .def_property_readonly("lengths", [](const Robot& r) {
        const RobotParams& p = r.params();
        py::dict d;
        d["l1"] = p.l1;
        d["l2"] = p.l2;
        d["l4"] = p.l4;
        d["l5"] = p.l5;
        return d;
      }, "tibias l1, l5 and femurs l2, l4 [m]")
      .def_property_readonly("masses", [](const Robot& r) { return vectorArray(r.params().mass); },
                             "m1..m5 as in the file [kg] (trunk without the support bar)")
      .def_property_readonly("com_offsets", [](const Robot& r) { return vectorArray(r.params().s); })
      .def_property_readonly("inertias", [](const Robot& r) { return vectorArray(r.params().inertia); })
      .def_property_readonly("rotor_inertia",
                             [](const Robot& r) { return vectorArray(r.params().rotor_inertia); })
      .def_property_readonly("gear_ratio", [](const Robot& r) { return r.params().gear_ratio; })
      .def_property_readonly("coulomb", [](const Robot& r) { return vectorArray(r.params().coulomb); })
      .def_property_readonly("viscous", [](const Robot& r) { return vectorArray(r.params().viscous); })
      .def_property_readonly("gravity", [](const Robot& r) { return r.params().gravity; })
      .def_property_readonly("trunk_length", [](const Robot& r) { return r.params().trunk_length; })
      .def_property_readonly("support_bar_mass",
                             [](const Robot& r) { return r.params().bar.equivalent_mass; })
      .def_property_readonly("total_mass", [](const Robot& r) { return r.model().total_mass; },
                             "mass of the model [kg], the support bar folded in (1.24)")
      .def("model", &Robot::modelReport, py::arg("q"), py::arg("qd") = py::none(),
           py::arg("qdd") = py::none(),
           "Model terms at (q, qd[, qdd]) as a dict: the JSON of `gaitopt model`")
      .def("impact", &Robot::impact, py::arg("q"), py::arg("qd"), py::arg("mu"),
           py::arg("model") = "algebraic",
           "Rigid impact of foot 2 at the pinned state (q, qd) as a dict: the JSON of "
           "`gaitopt impact` (every consistent solution)");
}

void bindGait(py::module_& m) {
  py::class_<Gait>(m, "Gait", "A gait file read by the library (loadGaitFile)")
      .def(py::init<const std::string&>(), py::arg("path"))
      .def_property_readonly("path", [](const Gait& g) { return g.file.path; })
      .def_property_readonly("robot_path", [](const Gait& g) { return g.file.robot_path; })
      .def_property_readonly("robot", &Gait::robot)
      .def_property_readonly("parameters", [](const Gait& g) { return vectorArray(g.file.parameters); },
                             "the parameter vector (a copy), in the order of parameter_names")
      .def_property_readonly("parameter_names",
                             [](const Gait& g) { return parameterNames(g.file.options); })
      .def_property_readonly("parameterisation",
                             [](const Gait& g) { return g.file.options.parameterisation.label(); })
      .def_property_readonly("sample_rate", [](const Gait& g) { return g.file.options.sample_rate; })
      .def_property_readonly("target_speed", [](const Gait& g) {
        return noneUnless(g.file.options.target_speed > 0.0, g.file.options.target_speed);
      });

  py::class_<Trajectory>(m, "Trajectory",
                         "One step sampled by the library (t from SS start; positions in the "
                         "stance foot's frame; one row per sample)")
      .def_readonly("t", &Trajectory::t)
      .def_readonly("phase", &Trajectory::phase, "'SS' or 'DS' per sample")
      .def_readonly("q", &Trajectory::q, "alpha, delta1..delta4 [rad]")
      .def_readonly("qd", &Trajectory::qd)
      .def_readonly("qdd", &Trajectory::qdd)
      .def_readonly("torques", &Trajectory::torques, "motor torques Gamma*_1..4 [N m]")
      .def_readonly("reactions", &Trajectory::reactions, "R1x, R1z, R2x, R2z [N]")
      .def_readonly("foot2", &Trajectory::foot2, "swing foot in SS, rear foot in DS (x, z) [m]")
      .def_readonly("com", &Trajectory::com)
      .def_readonly("knee1", &Trajectory::knee1)
      .def_readonly("hip", &Trajectory::hip)
      .def_readonly("knee2", &Trajectory::knee2)
      .def_readonly("head", &Trajectory::head)
      .def_readonly("omega", &Trajectory::omega, "joint speeds [rad/s]")
      .def_readonly("gamma_max", &Trajectory::gamma_max, "envelope torques at omega [N m]")
      .def_readonly("sigma", &Trajectory::sigma, "angular momentum about foot 1 [kg m^2/s]")
      .def_readonly("clearance", &Trajectory::clearance, "clearance bound (3.49) [m]");

  py::class_<Evaluation>(m, "Evaluation", "One evaluated parameter vector")
      .def_property_readonly("parameters", [](const Evaluation& e) { return vectorArray(e.parameters); })
      .def_property_readonly("defined", [](const Evaluation& e) { return e.value.defined(); })
      .def_property_readonly("motion_computed", [](const Evaluation& e) { return e.value.motion_computed; })
      .def_property_readonly("failed_level", [](const Evaluation& e) {
        return noneUnless(e.verdict.failed_level >= 0, e.verdict.failed_level);
      }, "lowest level with an unmet constraint (5 for the speed), None when feasible")
      .def_property_readonly("feasible", [](const Evaluation& e) { return e.verdict.feasible; })
      .def_property_readonly("unmet_constraints",
                             [](const Evaluation& e) { return e.verdict.unmet_groups; })
      .def_property_readonly("C_Gamma",
                             [](const Evaluation& e) { return noneUnless(e.hasCriteria(), e.value.C_Gamma); })
      .def_property_readonly("C_E", [](const Evaluation& e) { return noneUnless(e.hasCriteria(), e.value.C_E); })
      .def_property_readonly("W", [](const Evaluation& e) { return noneUnless(e.hasCriteria(), e.value.W); })
      .def_property_readonly("C_frott",
                             [](const Evaluation& e) { return noneUnless(e.hasCriteria(), e.value.C_frott); })
      .def_property_readonly("speed", [](const Evaluation& e) { return noneUnless(e.hasTiming(), e.value.speed); })
      .def_property_readonly("T_SS", [](const Evaluation& e) { return noneUnless(e.hasTiming(), e.value.T_SS); })
      .def_property_readonly("T_DS", [](const Evaluation& e) { return e.value.T_DS; })
      .def_property_readonly("step_length", [](const Evaluation& e) { return e.value.step_length; })
      .def_property_readonly("g", [](const Evaluation& e) { return vectorArray(e.value.g); },
                             "constraint vector, g <= 0 when satisfied")
      .def_property_readonly("g_levels", &Evaluation::levels, "hierarchy level of each entry of g")
      .def_property_readonly("constraints", &Evaluation::constraints,
                             "per group: name, level, equation, unit, offset, count, values "
                             "(its slice of g), defined, value (worst defined entry or None)")
      .def("trajectory", &Evaluation::trajectory, py::arg("sample_rate") = py::none(),
           "The step sampled at sample_rate (default: the gait's), None when undefined");

  py::class_<Evaluator>(m, "GaitEvaluator", "The evaluator of a gait's robot and options")
      .def(py::init<const Gait&>(), py::arg("gait"))
      .def_property_readonly("parameter_names",
                             [](const Evaluator& e) { return parameterNames(e.evaluator->options()); })
      .def_property_readonly("num_parameters", [](const Evaluator& e) { return e.evaluator->numParameters(); })
      .def("evaluate", &Evaluator::evaluate, py::arg("parameters") = py::none(),
           "Evaluate a parameter vector (default: the gait's)");
  m.def("evaluate", [](const std::string& path) { return Evaluator(Gait(path)).evaluate({}); },
        py::arg("gait"), "Evaluate a gait file's parameters");
}

void bindOptimization(py::module_& m) {
  py::class_<Optimization>(m, "OptimizationResult", "The library's optimisation result")
      .def_property_readonly("parameters", [](const Optimization& o) { return vectorArray(o.result.parameters); })
      .def_property_readonly("status",
                             [](const Optimization& o) {
                               return std::string(optimizationStatusName(o.result.status));
                             })
      .def_property_readonly("iterations", [](const Optimization& o) { return o.result.iterations; })
      .def_property_readonly("function_evaluations",
                             [](const Optimization& o) { return o.result.function_evaluations; })
      .def_property_readonly("gradient_evaluations",
                             [](const Optimization& o) { return o.result.gradient_evaluations; })
      .def_property_readonly("wall_time_s", [](const Optimization& o) { return o.result.wall_time_s; })
      .def_property_readonly("constraint_violation",
                             [](const Optimization& o) { return o.result.constraint_violation; })
      .def_property_readonly("unmet_level", [](const Optimization& o) {
        return noneUnless(o.result.unmet_level >= 0, o.result.unmet_level);
      })
      .def_property_readonly("unmet_constraints", [](const Optimization& o) { return o.result.unmet_constraints; })
      .def_property_readonly("stages", [](const Optimization& o) {
        py::list stages;
        for (const StageReport& s : o.result.stages) {
          py::dict d;
          d["name"] = s.name;
          d["status"] = nlpStatusName(s.status);
          d["iterations"] = s.iterations;
          stages.append(d);
        }
        return stages;
      })
      .def_readonly("evaluation", &Optimization::evaluation, "the evaluation of `parameters`")
      .def_readonly("gait_yaml", &Optimization::gait_yaml, "gait.yaml of the result");
  m.def("optimize", &optimize, py::arg("config"), py::arg("out") = py::none(),
        "Optimise as `gaitopt optimize --config CONFIG`: an OptimizationResult; writes "
        "summary.json, gait.yaml and trajectory.csv into the folder `out` when given, published "
        "together (OutputError for an unusable `out`)");
}

}  // namespace
}  // namespace gaitopt

PYBIND11_MODULE(gaitopt, m) {
  using namespace gaitopt;
  m.doc() = "gaitopt: optimal walking gaits for RABBIT-class planar bipeds (libgaitopt bindings)";
  m.attr("__version__") = GAITOPT_VERSION;
  m.attr("git_describe") = GAITOPT_GIT_DESCRIBE;
  // Bad robot, gait or optimiser files: the reader's message (file:line: key: problem).
  py::register_exception<ConfigError>(m, "ConfigError", PyExc_ValueError);
  py::register_exception<OutputError>(m, "OutputError", PyExc_ValueError);
  bindRobot(m);
  bindGait(m);
  bindOptimization(m);
  m.def("diagnose", &diagnoseData, py::arg("robot"), py::arg("data"), py::arg("holdout") = 3,
        py::arg("out") = py::none(),
        "Diagnose a robot model on measured data as `gaitopt diagnose`: the diagnosis' fields "
        "as a dict (causes, candidates, channel reports, residuals as NumPy arrays, "
        "extended_robot as a Robot, ...) plus 'report', 'residuals_csv' and "
        "'extended_robot_yaml' (texts); writes the four files into the folder `out` when given, "
        "published together (OutputError for an unusable `out`)");
  m.def("export", &exportGait, py::arg("gait"), py::arg("steps") = 10, py::arg("rate") = 1000.0,
        py::arg("first_stance") = "left", py::arg("format") = "csv", py::arg("out") = py::none(),
        "Export N steps for a controller as `gaitopt export`: the JSON document as a dict "
        "(metadata, units, samples as numpy arrays by column, phases); writes `out` (csv or "
        "json by `format`) when given");
}
