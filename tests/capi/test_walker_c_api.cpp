// The C interface of the reference walker (libgaitopt_walker.so) as a user links it: loading a
// JSON export, the options and every error path, the information and the initial state against
// the library's own values, torques at the initial state.
#include <catch2/catch.hpp>

#include <fstream>
#include <string>

#include "gaitopt/control/walker.h"
#include "gaitopt/control/walker.hpp"
#include "gaitopt/export/controller_export.hpp"
#include "test_default_gait.hpp"
#include "test_files.hpp"

namespace gaitopt::test {
namespace {

std::string exportedJson(const ShippedGait& g) {
  static ScratchDir dir("walker_c_api");
  ExportRequest req;
  req.steps = 1;
  req.rate = 200;
  const std::string path = dir.fresh("export") + ".json";
  std::ofstream(path) << exportJson(g.gait, g.model, g.evaluation,
                                    exportMetadata(g.gait, g.evaluation, req),
                                    exportTrajectory(g.evaluator, g.evaluation, g.model, req));
  return path;
}

std::string loadError(const std::string& path, const char* options) {
  char error[512] = "unchanged";
  gaitopt_walker* w = gaitopt_walker_load(path.c_str(), options, error, sizeof error);
  CHECK(w == nullptr);
  gaitopt_walker_free(w);
  return error;
}

}  // namespace

TEST_CASE("C walker loads an export and agrees with the library", "[capi][walker]") {
  const DefaultGait g;
  const std::string path = exportedJson(g);
  char error[256] = "";
  gaitopt_walker* w = gaitopt_walker_load(path.c_str(), "gain_scale: 2", error, sizeof error);
  REQUIRE(w != nullptr);
  CHECK(std::string(error).empty());
  gaitopt_walker_info info;
  REQUIRE(gaitopt_walker_get_info(w, &info) == 0);
  CHECK(info.speed == Approx(g.evaluation.speed).epsilon(1e-12));
  CHECK(gaitopt_walker_speed(w) == info.speed);
  CHECK(info.step_length == Approx(g.evaluation.step_length).epsilon(1e-12));
  CHECK(info.t_ss == Approx(g.evaluation.T_SS).epsilon(1e-12));
  CHECK(info.t_ds == Approx(g.evaluation.T_DS).epsilon(1e-12));
  for (double t : info.torque_max) CHECK(t == g.model.robot.envelope.torque[0]);
  CHECK(std::string(info.robot_file) == g.gait.robot_path);

  gaitopt_walker_state s;
  REQUIRE(gaitopt_walker_initial_state(w, &s) == 0);
  const WalkerState ref = Walker(g.model, g.evaluation, g.gait.options.parameterisation,
                                 walkerOptionsFor(g.gait.options, g.model))
                              .initialState();
  CHECK(s.pitch == ref.pitch);
  CHECK(s.x_hip == ref.hip(0));
  CHECK(s.zd_hip == ref.hip_rate(1));
  for (int j = 0; j < 4; ++j) CHECK(s.phid[j] == ref.phi_rate(j));
  CHECK(s.contact[0] == 1);
  CHECK(s.contact[1] == 0);
  double tau[4] = {0, 0, 0, 0};
  CHECK(gaitopt_walker_torques(w, &s, tau) == 0);
  for (double t : tau) CHECK(std::abs(t) <= info.torque_max[0]);
  s.pitch = 1.5;
  s.t = 0.001;
  CHECK(gaitopt_walker_torques(w, &s, tau) == 1);
  gaitopt_walker_free(w);
}

TEST_CASE("C walker reports NULL arguments and bad input with the file or key",
          "[capi][walker]") {
  const DefaultGait g;
  const std::string path = exportedJson(g);
  CHECK(loadError(path, "gain_scale: 2\nbandwith: 30").find("bandwith") != std::string::npos);
  CHECK(loadError(path, "gain_scale: -1").find("gain_scale") != std::string::npos);
  CHECK(loadError(path, "lean_gain: -0.1").find("lean_gain") != std::string::npos);
  CHECK(loadError(path, "max_lean: 0").find("max_lean") != std::string::npos);
  CHECK(loadError(path, "slope_compensation: -1").find("slope_compensation") !=
        std::string::npos);
  CHECK(loadError(path, "apex_energy_fraction: -0.5").find("apex_energy_fraction") !=
        std::string::npos);
  gaitopt_walker* w = gaitopt_walker_load(
      path.c_str(),
      "lean_gain: 0\nlean_integral_gain: 0\nslope_compensation: 0\nslope_deadband: 0.01\n"
      "max_lean: 0.2\napex_energy_fraction: 0.3",
      nullptr, 0);
  CHECK(w != nullptr);
  gaitopt_walker_free(w);
  CHECK(loadError(path, "ds_control: fast").find("expected cubic or time_optimal") !=
        std::string::npos);
  CHECK(loadError(path + ".missing", nullptr).find(path + ".missing") != std::string::npos);
  CHECK(loadError(sourcePath("configs/gait/default_step.yaml"), nullptr)
            .find("default_step.yaml") != std::string::npos);
  CHECK(gaitopt_walker_load(nullptr, nullptr, nullptr, 0) == nullptr);
  gaitopt_walker_state s;
  gaitopt_walker_info info;
  double tau[4];
  CHECK(gaitopt_walker_initial_state(nullptr, &s) == -1);
  CHECK(gaitopt_walker_get_info(nullptr, &info) == -1);
  CHECK(gaitopt_walker_torques(nullptr, &s, tau) == -1);
  CHECK(gaitopt_walker_speed(nullptr) == 0.0);
  // A truncated message still ends in NUL.
  char small[8];
  CHECK(gaitopt_walker_load((path + ".missing").c_str(), nullptr, small, sizeof small) == nullptr);
  CHECK(std::string(small).size() == 7);
}

}  // namespace gaitopt::test
