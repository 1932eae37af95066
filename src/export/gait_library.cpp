#include "gaitopt/export/gait_library.hpp"

#include <filesystem>
#include <stdexcept>

#include "gaitopt/export/controller_export.hpp"
#include "gaitopt/io/controller_export_file.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/file_digest.hpp"
#include "gaitopt/io/sweep_file.hpp"

namespace gaitopt {
namespace {

// A library gait evaluated with the feedforward's model; ConfigError at the gait file when it
// cannot be written as polynomials.
struct EvaluatedGait {
  GaitEvaluation<double> evaluation;
  Model model;
};

EvaluatedGait evaluated(const GaitFile& g, RotorModel rotor) {
  if (g.options.parameterisation.basis == PathBasis::BSpline)
    throw ConfigError(g.path, "parameterisation.basis", 0,
                      "the gait library writes each virtual constraint as one polynomial, got "
                      "'bspline'");
  const GaitEvaluator evaluator(g.robot, g.options, g.model_options);
  ModelOptions feedforward = g.model_options;
  feedforward.rotor = rotor;
  // The feedforward overcomes the robot file's whole friction, as in the controller export.
  EvaluatedGait e{evaluator.evaluate(g.parameters), buildModel(g.robot, feedforward)};
  if (!e.evaluation.defined() || !e.evaluation.motion_computed)
    throw ConfigError(g.path, "parameters", 0,
                      "the step is undefined (failed level " +
                          std::to_string(e.evaluation.failed_level) + ")");
  return e;
}

}  // namespace

std::vector<LibraryGait> loadSweepGaits(const std::string& dir) {
  const std::string csv_path = (std::filesystem::path(dir) / "sweep.csv").string();
  std::string csv;
  try {
    csv = mergeShardSweepCsvs({dir});
  } catch (const std::invalid_argument& e) {
    throw ConfigError(csv_path, "", 0, e.what());
  }
  std::vector<double> speeds;
  std::vector<bool> optimal;
  std::size_t start = csv.find('\n') + 1;  // after the header
  for (std::size_t end; (end = csv.find('\n', start)) != std::string::npos; start = end + 1) {
    const std::vector<std::string> fields = splitFields(csv.substr(start, end - start));
    speeds.push_back(parseCsvNumber(fields[0], csv_path, "speed", 0));
    optimal.push_back(fields[1] == "optimal");
  }
  const int decimals = sweepFolderDecimals(speeds);
  std::vector<LibraryGait> gaits;
  for (std::size_t i = 0; i < speeds.size(); ++i) {
    if (!optimal[i]) continue;
    LibraryGait g{speeds[i], sweepFolderName(speeds[i], decimals), {}};
    g.gait = loadGaitFile((std::filesystem::path(dir) / g.folder / "gait.yaml").string());
    gaits.push_back(g);
  }
  if (gaits.empty()) throw ConfigError(csv_path, "status", 0, "no speed is optimal");
  return gaits;
}

std::string gaitLibraryJson(const std::vector<LibraryGait>& gaits, RotorModel rotor) {
  if (gaits.empty()) throw std::invalid_argument("gaitLibraryJson: no gait");
  const std::string robot_sha = fileSha256(gaits.front().gait.robot_path);
  std::vector<EvaluatedGait> evaluations;
  for (const LibraryGait& g : gaits) {
    if (fileSha256(g.gait.robot_path) != robot_sha)
      throw ConfigError(g.gait.path, "robot", 0,
                        "names robot file '" + g.gait.robot_path + "', which differs from '" +
                            gaits.front().gait.robot_path + "' of the library's first gait");
    evaluations.push_back(evaluated(g.gait, rotor));
  }
  JsonWriter w;
  w.beginObject();
  w.key("format").value("gaitopt gait library");
  w.key("schema_version").value(kControllerExportSchema);
  writeEmbeddedFile(w, "robot", gaits.front().gait.robot_path);
  writeFeedforwardHead(w, evaluations.front().model);
  writeExportConventions(w);
  w.key("gaits").beginArray();
  for (std::size_t i = 0; i < gaits.size(); ++i) {
    w.beginObject();
    w.key("speed").value(gaits[i].speed);
    w.key("folder").value(gaits[i].folder);
    writeEmbeddedFile(w, "gait", gaits[i].gait.path);
    writeCyclicGait(w, evaluations[i].evaluation);
    writeExportPhases(w, evaluations[i].model, evaluations[i].evaluation.motion);
    w.endObject();
  }
  w.endArray();
  w.endObject();
  return w.str() + "\n";
}

}  // namespace gaitopt
