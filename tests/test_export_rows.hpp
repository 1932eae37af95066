#pragma once
// Comparison of exported rows (controller export and ramp round trips).
#include <catch2/catch.hpp>

#include <yaml-cpp/yaml.h>

#include "gaitopt/export/controller_export.hpp"
#include "test_default_gait.hpp"

namespace gaitopt::test {

inline void requireRowsEqual(const ExportRow& a, const ExportRow& b, double tol) {
  CHECK(a.step == b.step);
  CHECK(a.phase == b.phase);
  CHECK(a.stance == b.stance);
  CHECK(a.event == b.event);
  CHECK(a.t == Approx(b.t).margin(tol));
  CHECK(a.s == Approx(b.s).margin(tol));
  CHECK(a.sd == Approx(b.sd).margin(tol));
  CHECK(a.sdd == Approx(b.sdd).margin(tol));
  CHECK(a.alpha == Approx(b.alpha).margin(tol));
  CHECK(a.alphad == Approx(b.alphad).margin(tol));
  CHECK(a.alphadd == Approx(b.alphadd).margin(tol));
  CHECK((a.hip - b.hip).norm() <= tol);
  CHECK(a.trunk_angle == Approx(b.trunk_angle).margin(tol));
  for (const auto& [x, y] : {std::pair{a.phi, b.phi}, {a.phid, b.phid}, {a.phidd, b.phidd},
                             {a.motor, b.motor}, {a.tau, b.tau}, {a.tau_inertial, b.tau_inertial},
                             {a.tau_gravity, b.tau_gravity}, {a.tau_contact, b.tau_contact},
                             {a.tau_friction, b.tau_friction}, {a.tau_B, b.tau_B},
                             {a.tau_C, b.tau_C}})
    CHECK((x - y).lpNorm<Eigen::Infinity>() <= tol);
  for (const auto& [x, y] : {std::pair{a.foot_left, b.foot_left}, {a.foot_right, b.foot_right},
                             {a.R_left, b.R_left}, {a.R_right, b.R_right}})
    CHECK((x - y).lpNorm<Eigen::Infinity>() <= tol);
}

// One step of a shipped gait exported at `rate`: the rows and the JSON document read back.
struct ExportedJson {
  std::vector<ExportRow> rows;
  YAML::Node doc;
};

inline ExportedJson exportedJson(const ShippedGait& f, double rate) {
  ExportRequest req;
  req.rate = rate;
  ExportedJson out;
  out.rows = exportTrajectory(f.evaluator, f.evaluation, f.model, req);
  out.doc = YAML::Load(exportJson(f.gait, f.model, f.evaluation,
                                  exportMetadata(f.gait, f.evaluation, req), out.rows));
  return out;
}

}  // namespace gaitopt::test
