// `import gaitopt`: thin pybind11 bindings over libgaitopt. Every result is the document the CLI
// writes (model JSON, summary.json, trajectory.csv), parsed into Python objects, so the values
// are those of the CLI by construction; file errors raise gaitopt.ConfigError with the CLI's
// message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/gait/evaluator.hpp"
#include "gaitopt/ident/diagnose.hpp"
#include "gaitopt/impact/solve_impact.hpp"
#include "gaitopt/io/impact_report.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/gait/summary.hpp"
#include "gaitopt/gait/trajectory.hpp"
#include "gaitopt/io/atomic_file.hpp"
#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "gaitopt/io/measured_data.hpp"
#include "gaitopt/io/model_report.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/io/optimize_output.hpp"
#include "gaitopt/io/robot_file.hpp"
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

// trajectory.csv as {column: numpy array}; the phase column as a numpy array of str, empty
// fields (zd_potential in DS) as NaN.
py::dict trajectoryColumns(const std::string& csv) {
  std::istringstream in(csv);
  std::string line, cell;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::istringstream h(line); std::getline(h, cell, ',');) names.push_back(cell);
  std::vector<std::vector<double>> numbers(names.size());
  std::vector<std::string> phase;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    for (std::size_t j = 0; j < names.size(); ++j) {
      if (!std::getline(row, cell, ',')) cell.clear();  // a trailing empty field
      if (names[j] == "phase") phase.push_back(cell);
      else numbers[j].push_back(cell.empty() ? std::nan("") : std::stod(cell));
    }
  }
  py::dict columns;
  const py::object array = py::module_::import("numpy").attr("array");
  for (std::size_t j = 0; j < names.size(); ++j)
    columns[py::str(names[j])] = names[j] == "phase" ? array(phase) : array(numbers[j]);
  return columns;
}

py::dict withTrajectory(const std::string& summary_json, const std::optional<std::string>& csv) {
  py::dict result = fromJson(summary_json);
  result["trajectory"] = csv ? py::object(trajectoryColumns(*csv)) : py::object(py::none());
  return result;
}

class Robot {
 public:
  Robot(const std::string& path, const std::string& rotor) {
    if (rotor != "exact" && rotor != "high_gear")
      throw py::value_error("rotor: 'exact' or 'high_gear' expected, got '" + rotor + "'");
    ModelOptions options;
    options.rotor = rotor == "exact" ? RotorModel::Exact : RotorModel::HighGear;
    model_ = buildModel(loadRobot(path), options);
  }
  std::string name() const { return model_.robot.name; }
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
  // The document of `gaitopt model --q ... [--qd ...] [--qdd ...]`.
  py::object model(const std::vector<double>& q, const std::optional<std::vector<double>>& qd,
                   const std::optional<std::vector<double>>& qdd) const {
    std::optional<Vec5> acc;
    if (qdd) acc = toVec5(*qdd, "qdd");
    return fromJson(modelReportJson(model_, toVec5(q, "q"),
                                    qd ? toVec5(*qd, "qd") : Vec5(Vec5::Zero()), acc));
  }

 private:
  Model model_;
};

// As `gaitopt evaluate --gait FILE`: summary.json as a dict plus "trajectory" (None when the
// step is undefined).
py::dict evaluate(const std::string& gait_path, std::optional<double> sample_rate) {
  GaitFile gait = loadGaitFile(gait_path);
  if (sample_rate) gait.options.sample_rate = *sample_rate;
  const GaitEvaluator evaluator(gait.robot, gait.options, gait.model_options);
  const GaitEvaluation<double> e = evaluator.evaluate(gait.parameters);
  std::optional<std::string> csv;
  if (e.defined() && e.motion_computed)
    csv = trajectoryCsv(sampleTrajectory(evaluator, e, gait.options.sample_rate));
  return withTrajectory(gaitSummaryJson(evaluator, gait.parameters, e), csv);
}

// As `gaitopt optimize --config FILE --quiet [--out DIR]`: summary.json as a dict plus
// "trajectory" and "gait_yaml"; the files are written only when `out` is given.
py::dict optimize(const std::string& config_path, const std::optional<std::string>& out) {
  const OptimizeConfig config = loadOptimizeConfig(config_path);
  OptimizationOutputs outputs;
  {
    py::gil_scoped_release release;  // a long run should not block other Python threads
    const GaitEvaluator evaluator(config.robot, config.options, config.model_options);
    const GaitParameters initial = configuredInitialGuess(config, evaluator.model());
    const OptimizationResult r =
        optimizeGait(evaluator, optimizationRequest(config, initial), nullptr);
    outputs = optimizationOutputs(evaluator, config, r, out.value_or("."));
    if (out) writeOptimizationOutputs(*out, outputs);
  }
  py::dict result = withTrajectory(outputs.summary_json, outputs.trajectory_csv);
  result["gait_yaml"] = outputs.gait_yaml;
  return result;
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
    json = exportJson(meta, rows, e);
    if (out) writeFileAtomically(*out, format == "csv" ? exportCsv(meta, rows) : json);
  }
  py::dict result = fromJson(json);
  const py::object array = py::module_::import("numpy").attr("array");
  py::dict samples = result["samples"];
  for (auto item : samples) samples[item.first] = array(item.second);
  return result;
}

// As `gaitopt diagnose --robot R --data D [--holdout K] [--out DIR]`: diagnosis.json as a
// dict plus "report" (report.md), "residuals_csv" and "extended_robot_yaml" (texts); the four
// files are written into `out` when given.
py::dict diagnoseData(const std::string& robot_path, const std::string& data_path, int holdout,
                      const std::optional<std::string>& out) {
  const RobotParams robot = loadRobot(robot_path);
  const MeasuredData data = readMeasuredCsv(data_path);
  DiagnoseOptions options;
  options.holdout = holdout;
  std::string json, csv, report, yaml;
  {
    py::gil_scoped_release release;
    Diagnosis d;
    try {
      d = diagnose(robot, ModelOptions{}, data, options);
    } catch (const std::invalid_argument& e) {
      throw py::value_error(std::string("holdout: ") + e.what());
    }
    json = diagnosisJson(d);
    csv = residualsCsv(data, d);
    report = diagnosisReport(d);
    yaml = extendedRobotYaml(robot_path, d.extended_robot);
    if (out) {
      std::filesystem::create_directories(*out);
      const std::filesystem::path dir(*out);
      writeFileAtomically((dir / "diagnosis.json").string(), json);
      writeFileAtomically((dir / "residuals.csv").string(), csv);
      writeFileAtomically((dir / "report.md").string(), report);
      writeFileAtomically((dir / "extended_robot.yaml").string(), yaml);
    }
  }
  py::dict result = fromJson(json);
  result["report"] = report;
  result["residuals_csv"] = csv;
  result["extended_robot_yaml"] = yaml;
  return result;
}

}  // namespace
}  // namespace gaitopt

PYBIND11_MODULE(gaitopt, m) {
  using namespace gaitopt;
  m.doc() = "gaitopt: optimal walking gaits for RABBIT-class planar bipeds (libgaitopt bindings)";
  m.attr("__version__") = GAITOPT_VERSION;
  m.attr("git_describe") = GAITOPT_GIT_DESCRIBE;
  // Bad robot, gait or optimiser files: the message of the CLI's "gaitopt: error: ..." line.
  py::register_exception<ConfigError>(m, "ConfigError", PyExc_ValueError);
  py::class_<Robot>(m, "Robot", "A robot description file (as `gaitopt model --robot`)")
      .def(py::init<const std::string&, const std::string&>(), py::arg("path"),
           py::arg("rotor") = "exact")
      .def_property_readonly("name", &Robot::name)
      .def("model", &Robot::model, py::arg("q"), py::arg("qd") = py::none(),
           py::arg("qdd") = py::none(),
           "Model terms at (q, qd[, qdd]) as a dict: the JSON of `gaitopt model`")
      .def("impact", &Robot::impact, py::arg("q"), py::arg("qd"), py::arg("mu"),
           py::arg("model") = "algebraic",
           "Rigid impact of foot 2 at the pinned state (q, qd) as a dict: the JSON of "
           "`gaitopt impact` (every consistent solution)");
  m.def("evaluate", &evaluate, py::arg("gait"), py::arg("sample_rate") = py::none(),
        "Evaluate a gait file: summary.json as a dict, plus 'trajectory' (numpy arrays by "
        "trajectory.csv column, None for an undefined step)");
  m.def("optimize", &optimize, py::arg("config"), py::arg("out") = py::none(),
        "Optimise as `gaitopt optimize --config CONFIG`: summary.json as a dict, plus "
        "'trajectory' and 'gait_yaml'; writes the files into `out` when given");
  m.def("diagnose", &diagnoseData, py::arg("robot"), py::arg("data"), py::arg("holdout") = 3,
        py::arg("out") = py::none(),
        "Diagnose a robot model on measured data as `gaitopt diagnose`: diagnosis.json as a "
        "dict plus 'report', 'residuals_csv' and 'extended_robot_yaml' (texts); writes the four "
        "files into `out` when given");
  m.def("export", &exportGait, py::arg("gait"), py::arg("steps") = 10, py::arg("rate") = 1000.0,
        py::arg("first_stance") = "left", py::arg("format") = "csv", py::arg("out") = py::none(),
        "Export N steps for a controller as `gaitopt export`: the JSON document as a dict "
        "(metadata, units, samples as numpy arrays by column, phases); writes `out` (csv or "
        "json by `format`) when given");
}
