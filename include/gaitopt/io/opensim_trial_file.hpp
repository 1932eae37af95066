#pragma once
// An OpenSim walking trial read from its files (IK and GRF .mot, optional .trc markers) and
// converted (ident/opensim_import.hpp), and the measured-data CSV of the converted trial.
#include <string>
#include <utility>

#include "gaitopt/ident/data_error.hpp"
#include "gaitopt/ident/opensim_import.hpp"
#include "gaitopt/io/config_error.hpp"

namespace gaitopt {

struct OpenSimImportFiles {
  std::string ik;   // IK .mot: pelvis_tilt, pelvis_tx, pelvis_ty, hip_flexion_r/l, knee_angle_r/l, lumbar_extension
  std::string grf;  // GRF .mot: <prefix>vx, vy, px, py per plate
  std::string trc;  // optional ("" = none): markers for the trunk line and the belt speed
  std::string model;        // optional: the OpenSim model (.osim), for its name and knee sign
  std::string conventions;  // optional: conventions file (io/opensim_conventions_file.hpp)
};

// Least range of a knee angle over a walking trial [rad] (10 degrees; walking bends it ~60).
constexpr double kMinKneeRange = 0.17453292519943295;

// The tables of the files; ConfigError for a bad file (io/opensim_table.hpp, io/trc_file.hpp),
// for an IK file without inDegrees, and for one whose inDegrees flag disagrees with its angles: an angle the importer reads
// beyond half a turn (degrees declared as radians), or a knee moving less than kMinKneeRange
// (radians declared as degrees).
OpenSimRecording readOpenSimRecording(const OpenSimImportFiles& files);

// Reads and converts with the conventions of `files.conventions` and `files.model` (added to
// options.conventions) and, unless options give one, the pelvis_frame of robot.source_file; bad files or data that cannot be labelled are ConfigErrors naming the
// file.
ImportedTrial importOpenSimTrial(const OpenSimImportFiles& files, const RobotParams& robot,
                                 const OpenSimImportOptions& options = {});

// run(), with a DataError of the recorded data reported as the ConfigError of its file.
template <class Run>
decltype(auto) withDataErrorsAsConfigErrors(Run&& run) {
  try {
    return std::forward<Run>(run)();
  } catch (const DataError& e) {
    throw ConfigError(e.file(), e.key(), e.line(), e.problem());
  }
}

// The measured-data CSV (t, alpha, delta1..delta4, phase, stance, step, R1x, R1z, R2x, R2z,
// cop1x, cop2x).
std::string importedTrialCsv(const ImportedTrial& trial);

}  // namespace gaitopt
