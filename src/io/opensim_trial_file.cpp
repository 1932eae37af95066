#include "gaitopt/io/opensim_trial_file.hpp"

#include <cstdio>

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
  std::string out = "t,alpha,delta1,delta2,delta3,delta4,phase,stance,step,R1x,R1z,R2x,R2z\n";
  char buf[64];
  const auto number = [&](double v) {
    std::snprintf(buf, sizeof buf, "%.10g", v);
    out += buf;
  };
  for (Eigen::Index k = 0; k < trial.t.size(); ++k) {
    number(trial.t(k));
    for (int j = 0; j < 5; ++j) {
      out += ',';
      number(trial.q(k, j));
    }
    out += trial.double_support[k] ? ",DS," : ",SS,";
    out += sideName(trial.leg1[k]);
    out += ',' + std::to_string(trial.step[k]);
    for (int j = 0; j < 4; ++j) {
      out += ',';
      number(trial.reactions(k, j));
    }
    out += '\n';
  }
  return out;
}

}  // namespace gaitopt
