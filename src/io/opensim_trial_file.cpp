#include "gaitopt/io/opensim_trial_file.hpp"

#include <cmath>

#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/opensim_conventions_file.hpp"
#include "gaitopt/io/opensim_table.hpp"
#include "gaitopt/io/pelvis_frame_file.hpp"
#include "gaitopt/io/trc_file.hpp"
#include "gaitopt/io/yaml_reader.hpp"

namespace gaitopt {

namespace {

// The IK file's inDegrees flag checked against its joint angles: walking keeps every angle the
// importer reads within half a turn, and bends each knee by more than kMinKneeRange.
void checkAngleUnits(const OpenSimTable& ik) {
  if (!ik.units_declared)
    throw ConfigError(ik.file, "inDegrees", ik.first_data_line,
                      "missing from the header: the IK angles need inDegrees=yes or inDegrees=no");
  const double unit = ik.in_degrees ? M_PI / 180.0 : 1.0;
  const char* const flag = ik.in_degrees ? "inDegrees=yes" : "inDegrees=no";
  for (const char* name : {"pelvis_tilt", "lumbar_extension", "hip_flexion_r", "hip_flexion_l",
                           "knee_angle_r", "knee_angle_l"}) {
    if (!ik.hasColumn(name)) continue;  // the importer names a missing column
    Eigen::Index row = 0;
    const Eigen::VectorXd angle = unit * ik.column(name);
    if (angle.cwiseAbs().maxCoeff(&row) > M_PI)
      throw ConfigError(ik.file, name, ik.first_data_line + static_cast<int>(row),
                        "angle " + showNumber(angle(row)) + " rad with " + flag +
                            " is beyond half a turn: degrees declared as radians?");
    const bool knee = std::string(name).rfind("knee", 0) == 0;
    if (knee && ik.rows() > 0 && angle.maxCoeff() - angle.minCoeff() < kMinKneeRange)
      throw ConfigError(ik.file, name, ik.first_data_line,
                        "the knee moves by less than " + showNumber(kMinKneeRange * 180.0 / M_PI) +
                            " degrees over the trial with " + flag +
                            ": radians declared as degrees?");
  }
}

}  // namespace

OpenSimRecording readOpenSimRecording(const OpenSimImportFiles& files) {
  OpenSimRecording r;
  r.ik = readOpenSimTable(files.ik);
  checkAngleUnits(r.ik);
  r.grf = readOpenSimTable(files.grf);
  if (!files.trc.empty()) r.trc = readTrcFile(files.trc);
  return r;
}

ImportedTrial importOpenSimTrial(const OpenSimImportFiles& files, const RobotParams& robot,
                                 const OpenSimImportOptions& options) {
  OpenSimImportOptions with_hints = options;
  if (!files.conventions.empty()) with_hints.conventions = readConventionsFile(files.conventions);
  if (!files.model.empty()) addModelHints(files.model, with_hints.conventions);
  if (!with_hints.pelvis_frame && !robot.source_file.empty())
    with_hints.pelvis_frame = loadPelvisFrame(robot.source_file);
  const OpenSimRecording recording = readOpenSimRecording(files);
  return withDataErrorsAsConfigErrors(
      [&] { return importOpenSimTrial(recording, robot, with_hints); });
}

std::string importedTrialCsv(const ImportedTrial& trial) {
  std::string out = csvHeader({"t", "alpha", "delta1", "delta2", "delta3", "delta4", "phase",
                               "stance", "step", "R1x", "R1z", "R2x", "R2z", "cop1x", "cop2x"});
  const char* const format = "%.10g";
  for (Eigen::Index k = 0; k < trial.t.size(); ++k) {
    CsvRow row;
    row.number(trial.t(k), format);
    for (int j = 0; j < 5; ++j) row.number(trial.q(k, j), format);
    row.text(trial.double_support[k] ? "DS" : "SS").text(sideName(trial.leg1[k]));
    row.integer(trial.step[k]);
    for (int j = 0; j < 4; ++j) row.number(trial.reactions(k, j), format);
    for (int j = 0; j < 2; ++j) row.number(trial.cop_x(k, j), format);
    out += row.line();
  }
  return out;
}

}  // namespace gaitopt
