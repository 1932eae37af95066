#pragma once
// How an OpenSim walking trial names and signs what the import reads: the force-plate column
// prefix of each foot, the sign of knee_angle in flexion (negative in gait10dof18musc and
// gait2392, positive in the Rajagopal family's walker knee), the IK column of each coordinate
// and the marker names. Each is taken from what the user gave, else detected from the files
// where they are unambiguous, else refused with the way to give it; every decision is stated.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "gaitopt/ident/recorded_tables.hpp"

namespace gaitopt {

enum class KneeFlexion { Negative, Positive };  // sign of knee_angle when the knee bends

// What the user or the model file says; empty = detect from the tables.
struct ConventionHints {
  std::optional<std::string> right_plate, left_plate;  // GRF column prefixes (…vx, vy, px, py)
  std::optional<KneeFlexion> knee;
  std::string knee_source;  // where `knee` came from ("conventions file", "model file ...")
  std::string model;        // model name from the .osim, "" when none was given
  std::map<std::string, std::string> coordinates;  // IK name used here → column in the file
  std::optional<std::vector<std::string>> pelvis_markers, shoulder_markers;
  std::optional<std::vector<std::string>> heel_markers;  // right, left
};

struct OpenSimConventions {
  std::string right_plate, left_plate;
  KneeFlexion knee = KneeFlexion::Negative;
  std::map<std::string, std::string> coordinates;  // all eight IK names used here
  std::vector<std::string> pelvis_markers, shoulder_markers, heel_markers;  // empty: no .trc
  std::vector<std::string> statements;  // one line per decision, printed and reported

  // The IK column of coordinate `name` (pelvis_tilt, pelvis_tx, pelvis_ty, hip_flexion_r/l,
  // knee_angle_r/l, lumbar_extension).
  const std::string& column(const std::string& name) const { return coordinates.at(name); }
};

// Resolves the conventions of `ik`, `grf` and `trc` (nullptr: no markers). DataError naming the
// file when a convention can be neither detected nor found as given: no or several candidate
// plate pairs, a knee_angle range that fits neither sign, a hint contradicting the data, a
// marker set not in the file.
OpenSimConventions resolveConventions(const OpenSimTable& ik, const OpenSimTable& grf,
                                      const TrcData* trc, const ConventionHints& hints);

}  // namespace gaitopt
