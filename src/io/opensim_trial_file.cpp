#include "gaitopt/io/opensim_trial_file.hpp"

#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/opensim_table.hpp"
#include "gaitopt/io/trc_file.hpp"

namespace gaitopt {

OpenSimRecording readOpenSimRecording(const OpenSimImportFiles& files) {
  OpenSimRecording r;
  r.ik = readOpenSimTable(files.ik);
  r.grf = readOpenSimTable(files.grf);
  if (!files.trc.empty()) r.trc = readTrcFile(files.trc);
  return r;
}

ImportedTrial importOpenSimTrial(const OpenSimImportFiles& files, const RobotParams& robot,
                                 const OpenSimImportOptions& options) {
  const OpenSimRecording recording = readOpenSimRecording(files);
  return withDataErrorsAsConfigErrors(
      [&] { return importOpenSimTrial(recording, robot, options); });
}

std::string importedTrialCsv(const ImportedTrial& trial) {
  std::string out = csvHeader({"t", "alpha", "delta1", "delta2", "delta3", "delta4", "phase",
                               "stance", "step", "R1x", "R1z", "R2x", "R2z"});
  const char* const format = "%.10g";
  for (Eigen::Index k = 0; k < trial.t.size(); ++k) {
    CsvRow row;
    row.number(trial.t(k), format);
    for (int j = 0; j < 5; ++j) row.number(trial.q(k, j), format);
    row.text(trial.double_support[k] ? "DS" : "SS").text(sideName(trial.leg1[k]));
    row.integer(trial.step[k]);
    for (int j = 0; j < 4; ++j) row.number(trial.reactions(k, j), format);
    out += row.line();
  }
  return out;
}

}  // namespace gaitopt
