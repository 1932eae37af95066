#pragma once
// The documents `gaitopt diagnose` writes for a Diagnosis (ident/diagnose.hpp):
// diagnosis.json, residuals.csv, report.md and extended_robot.yaml.
#include <string>
#include <vector>

#include "gaitopt/ident/diagnose.hpp"

namespace gaitopt {

std::string diagnosisJson(const Diagnosis& d);
std::string residualsCsv(const MeasuredData& data, const Diagnosis& d);
std::string diagnosisReport(const Diagnosis& d);

// The nominal robot file's document with the identified effects as extension keys
// (io/robot_extensions.hpp): a valid robot file.
std::string extendedRobotYaml(const std::string& robot_path, const RobotParams& extended);

// The four documents of one diagnosis of `data` against the robot file `robot_path`.
struct DiagnosisDocuments {
  std::string json, residuals_csv, report, extended_robot_yaml;
};
DiagnosisDocuments diagnosisDocuments(const std::string& robot_path, const MeasuredData& data,
                                      const Diagnosis& d);

// The names of the files of a diagnosis folder: diagnosis.json, residuals.csv, report.md,
// extended_robot.yaml.
std::vector<std::string> diagnosisFileNames();

// Writes the documents as new files into `dir`, the staging folder of an OutputTransaction's
// directory result, so that the four files appear together when it is published.
void writeDiagnosisFiles(const std::string& dir, const DiagnosisDocuments& documents);

}  // namespace gaitopt
