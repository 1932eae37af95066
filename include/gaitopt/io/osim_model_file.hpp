#pragma once
// Reading an OpenSim model file (.osim) into an OsimModel (ident/osim_model.hpp): the bodies'
// mass properties and the joints' frames, coordinates and CustomJoint transforms, from both
// layouts (OpenSim 3: a <Joint> inside each <Body>, parent_body and location/orientation in
// parent and child; OpenSim 4: <JointSet> with socket_parent_frame / socket_child_frame and
// <PhysicalOffsetFrame>s), and the enforced CoordinateCouplerConstraints. Muscles, markers, geometry and everything else are skipped.
#include <string>

#include "gaitopt/ident/osim_model.hpp"
#include "gaitopt/io/xml_document.hpp"

namespace gaitopt {

// Throws ConfigError (file, "<body or joint>.<element>", line, problem) for an unreadable
// file, XML outside the subset of io/xml_document.hpp, a missing or malformed value, a frame
// that names no body, an unknown transform function, a negative mass or a non-finite number.
OsimModel loadOsimModel(const std::string& path);

// The same from a parsed document; `file` names it in messages.
OsimModel parseOsimModel(const XmlElement& root, const std::string& file);

}  // namespace gaitopt
