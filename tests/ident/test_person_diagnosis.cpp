// diagnose on the two shipped people, imported with their centres of pressure: the foot moment
// is measured, so the rocker radius the diagnosis fits must agree with the one of the CoP travel
// alone, and the inertial stage, no longer soaking up a foot moment it cannot describe, is no
// cause. Both halves of `--holdout 2` (each leg's stances in turn) are diagnosed.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "gaitopt/ident/diagnose.hpp"
#include "gaitopt/io/measured_data.hpp"
#include "gaitopt/io/opensim_trial_file.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "test_opensim_data.hpp"

using namespace gaitopt;
using namespace gaitopt::test;

namespace {

MeasuredData imported(const OpenSimImportFiles& files, const RobotParams& robot,
                      const OpenSimImportOptions& options) {
  ScratchDir dir("person_diagnosis");
  const std::string path = dir.fresh("data") + ".csv";
  std::ofstream(path) << importedTrialCsv(importOpenSimTrial(files, robot, options));
  return readMeasuredCsv(path);
}

// Diagnoses both halves; the rocker_foot fit within 15 % of the CoP's radius (the acceptance of
// the measured centre of pressure) and no inertial cause on either.
void checkBothHalves(const RobotParams& robot, const MeasuredData& data) {
  REQUIRE(data.has_cop);
  for (int shift : {0, 1}) {
    INFO("--holdout 2 --holdout-shift " << shift);
    DiagnoseOptions o;
    o.holdout = 2;
    o.holdout_shift = shift;
    const Diagnosis d = diagnose(robot, ModelOptions{}, data, o);
    REQUIRE(d.cop.used);
    INFO("radius: CoP " << d.cop.radius_cop << " m, fit " << d.cop.radius_fit << " m");
    CHECK(d.cop.radius_cop > 0.2);  // a rolling foot, not a point foot (~0.3 × leg length)
    CHECK(std::abs(d.cop.difference_pct) <= 15.0);
    for (const Cause& c : d.causes) CHECK(c.effect.kind != EffectKind::Inertial);
    CHECK_FALSE(d.inertial.accepted);
  }
}

}  // namespace

TEST_CASE("diagnose the treadmill person: rocker radius of the CoP, no inertial cause",
          "[ident][opensim_diagnose]") {
  const RobotParams robot =
      loadRobot(std::string(GAITOPT_SOURCE_DIR) + "/configs/robot/human_subject01.yaml");
  checkBothHalves(robot, imported({opensimIk(), opensimGrf(), opensimTrc(), "", ""}, robot, {}));
}

TEST_CASE("diagnose the overground person: rocker radius of the CoP, no inertial cause",
          "[ident][opensim_diagnose]") {
  const RobotParams robot = loadRobot(rajagopalRobot());
  OpenSimImportOptions options;
  options.trunk_from_markers = false;  // --trunk model: the line consistent with the reactions
  checkBothHalves(robot, imported({rajagopalIk(), rajagopalGrf(), rajagopalTrc(), rajagopalModel(), ""},
                                  robot, options));
}
