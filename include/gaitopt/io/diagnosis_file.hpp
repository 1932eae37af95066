#pragma once
// The documents `gaitopt diagnose` writes for a Diagnosis (ident/diagnose.hpp):
// diagnosis.json, residuals.csv, report.md and extended_robot.yaml.
#include <string>

#include "gaitopt/ident/diagnose.hpp"

namespace gaitopt {

std::string diagnosisJson(const Diagnosis& d);
std::string residualsCsv(const MeasuredData& data, const Diagnosis& d);
std::string diagnosisReport(const Diagnosis& d);

// The nominal robot file's document with the identified effects as extension keys
// (io/robot_extensions.hpp): a valid robot file.
std::string extendedRobotYaml(const std::string& robot_path, const RobotParams& extended);

}  // namespace gaitopt
