// `gaitopt lump-osim` on the two shipped OpenSim models.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <optional>
#include <regex>
#include <string>

#include "gaitopt/io/file_digest.hpp"
#include "gaitopt/io/pelvis_frame_file.hpp"
#include "gaitopt/io/robot_file.hpp"
#include "test_files.hpp"
#include "test_opensim_data.hpp"
#include "test_support.hpp"

using namespace gaitopt;
using Catch::Matchers::Contains;

namespace {

RobotParams lumped(test::ScratchDir& dir, const std::string& model, std::string* text = nullptr,
                   std::optional<PelvisFrame>* frame = nullptr) {
  const std::string out = dir.fresh("robot") + ".yaml";
  const test::CliRun run = test::runCli("lump-osim --model " + test::quoted(model) + " --out " + test::quoted(out));
  INFO(run.out << run.err);
  REQUIRE(run.exit_code == 0);
  if (text) *text = test::readFile(out);
  if (frame) *frame = loadPelvisFrame(out);
  return loadRobot(out);
}

// The pelvis frames agree within `tol` [m, kg] and their masses make the trunk's m3.
void checkPelvisFrame(const std::optional<PelvisFrame>& a, const std::optional<PelvisFrame>& b,
                      double tol) {
  REQUIRE(a);
  REQUIRE(b);
  for (int k = 0; k < 2; ++k) {
    CHECK(a->hip[k] == Approx(b->hip[k]).margin(tol));
    CHECK(a->pelvis_com[k] == Approx(b->pelvis_com[k]).margin(tol));
    CHECK(a->back[k] == Approx(b->back[k]).margin(tol));
    CHECK(a->torso_com[k] == Approx(b->torso_com[k]).margin(tol));
  }
  CHECK(a->pelvis_mass == Approx(b->pelvis_mass).margin(tol));
  CHECK(a->torso_mass == Approx(b->torso_mass).margin(tol));
}

// The robot file's masses add up to `total` within their rounding to 6 significant digits.
void checkMassSum(const RobotParams& r, double total) {
  double sum = 0.0, rounding = 0.0;
  for (const double m : r.mass) {
    sum += m;
    rounding += 0.5 * std::pow(10.0, std::floor(std::log10(m)) - 5.0);
  }
  CHECK(sum == Approx(total).margin(rounding));
}

// The sum of every <mass> of an .osim file (each body has one).
double massesInFile(const std::string& path) {
  const std::string text = test::readFile(path);
  const std::regex mass("<mass>([^<]*)</mass>");
  double total = 0.0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), mass); it != std::sregex_iterator(); ++it)
    total += std::stod((*it)[1].str());
  return total;
}

}  // namespace

TEST_CASE("lump-osim: subject01.osim gives configs/robot/human_subject01.yaml", "[osim][cli]") {
  test::ScratchDir dir("lump_osim");
  std::string text;
  std::optional<PelvisFrame> frame;
  const std::string model = test::opensimFile("subject01.osim");
  const RobotParams r = lumped(dir, model, &text, &frame);
  const RobotParams shipped = loadRobot(test::sourcePath("configs/robot/human_subject01.yaml"));
  // The shipped file is this command's output, each value printed to 6 significant digits:
  // within one unit of its last digit.
  const auto unit = [](double v) {
    std::string s = std::to_string(v);
    s.erase(s.find_last_not_of('0') + 1);
    const std::size_t point = s.find('.');
    return std::pow(10.0, -static_cast<double>(s.size() - point - 1));
  };
  for (int i = 0; i < 5; ++i) {
    INFO("body " << i + 1);
    CHECK(r.mass[i] == Approx(shipped.mass[i]).margin(unit(shipped.mass[i])));
    CHECK(r.s[i] == Approx(shipped.s[i]).margin(unit(shipped.s[i])));
    CHECK(r.inertia[i] == Approx(shipped.inertia[i]).margin(unit(shipped.inertia[i])));
  }
  CHECK(r.l1 == Approx(shipped.l1).margin(unit(shipped.l1)));
  CHECK(r.l5 == Approx(shipped.l5).margin(unit(shipped.l5)));
  CHECK(r.gravity == shipped.gravity);
  CHECK(r.limits.knee_max == Approx(shipped.limits.knee_max));
  CHECK(r.limits.hip_min == Approx(shipped.limits.hip_min));
  // The femur is hip to knee of the scaled model: the knee's y translation at zero knee angle
  // is the generic spline (knots -0.3966 at -0.174533 rad and -0.395264 at 0.159149 rad, chord
  // -0.39590 at 0) times the scale factor 1.14724, and the x translation likewise (knots
  // -0.0031 and -0.005227). A cubic departs from its chord by at most h^2/8 |S''|: h = 0.334
  // rad and |S''| <= 0.007 m/rad^2 (second divided differences of the neighbouring knots) give
  // 1e-4 m before scaling.
  const double chord_y = -0.3966 + (0.174533 / (0.174533 + 0.159149)) * (-0.395264 + 0.3966);
  const double chord_x = -0.0031 + (0.174533 / (0.174533 + 0.159149)) * (-0.005227 + 0.0031);
  CHECK(r.l2 == Approx(1.14724 * std::hypot(chord_x, chord_y)).margin(1.14724 * 1e-4));
  CHECK(r.l4 == r.l2);
  checkMassSum(r, massesInFile(model));
  // The pelvis frame import-opensim places the links with: the shipped file's, rounded to
  // 0.1 mm and 1 g (the trunk masses sums of rounded segment masses: 1 g each).
  checkPelvisFrame(frame, loadPelvisFrame(test::sourcePath("configs/robot/human_subject01.yaml")), 1e-3);
  CHECK(frame->pelvis_mass + frame->torso_mass == Approx(r.mass[2]).margin(1e-5));
  // Provenance: the model's digest and what was dropped.
  CHECK_THAT(text, Contains("sha256 " + fileSha256(model)));
  CHECK_THAT(text, Contains("calcn_r + talus_r + tibia_r + toes_r: 5.09415 kg"));
  CHECK_THAT(text, Contains("18.2 mm forward of the axis, dropped"));
  CHECK_THAT(text, Contains("pelvis + torso: 44.4436 kg"));
  CHECK_THAT(text, Contains("behind the hip midpoint"));
}

TEST_CASE("lump-osim: the second shipped person, a Rajagopal-family model", "[osim][cli]") {
  test::ScratchDir dir("lump_osim");
  const std::string model = test::sourcePath("data/opensim-rajagopal-walk/subject_walk_scaled.osim");
  std::optional<PelvisFrame> frame;
  const RobotParams r = lumped(dir, model, nullptr, &frame);
  // The shipped robot file is this command's output.
  const std::string shipped_file = test::sourcePath("configs/robot/human_rajagopal_walk.yaml");
  const RobotParams shipped = loadRobot(shipped_file);
  checkPelvisFrame(frame, loadPelvisFrame(shipped_file), 1e-9);
  for (int i = 0; i < 5; ++i) {
    CHECK(shipped.mass[i] == Approx(r.mass[i]).epsilon(1e-5));
    CHECK(shipped.s[i] == Approx(r.s[i]).epsilon(1e-5));
    CHECK(shipped.inertia[i] == Approx(r.inertia[i]).epsilon(1e-5));
  }
  CHECK(shipped.l1 == Approx(r.l1).epsilon(1e-5));
  CHECK(shipped.l2 == Approx(r.l2).epsilon(1e-5));
  // Masses: the five links hold every body of the model (arms and patellae included).
  checkMassSum(r, massesInFile(model));
  // Lengths: the joint centres from the model's offset frames (all segment frames are aligned
  // with ground at zero angles; the walker knee's translation polynomials have no constant
  // term and its rotation polynomials' constant terms are below 1e-7 rad, so within 1e-5 m):
  // hip centre = femur origin; knee centre = femur_r_offset of walker_knee_r in the femur,
  // tibia_r_offset in the tibia; ankle centre = tibia_r_offset of ankle_r in the tibia.
  CHECK(r.l2 == Approx(std::hypot(-0.0047310501632865645, -0.3988529689622225)).margin(1e-5));
  CHECK(r.l1 == Approx(std::hypot(-0.011635086131000002 + 0.0094122494660169743,
                                  -0.46517425728 + 0.0041107449115833595)).margin(1e-5));
  CHECK(r.gravity == Approx(9.80665));
}

TEST_CASE("lump-osim: bad models and names are refused, nothing written", "[osim][cli]") {
  test::ScratchDir dir("lump_osim");
  const std::string out = dir.fresh("robot") + ".yaml";
  const std::string bad = dir.fresh("bad") + ".osim";
  std::ofstream(bad) << "<?xml version=\"1.0\"?>\n<OpenSimDocument Version=\"40000\">\n<Model>\n</OpenSimDocument>\n";
  test::CliRun run = test::runCli("lump-osim --model " + test::quoted(bad) + " --out " + test::quoted(out));
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Contains(bad + ":4: end tag 'OpenSimDocument' does not match 'Model' opened on line 3"));
  CHECK_FALSE(std::filesystem::exists(out));
  run = test::runCli("lump-osim --model " + test::quoted(test::opensimFile("subject01.osim")) + " --out " +
                     test::quoted(out) + " --thighs thigh_r,thigh_l");
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Contains("subject01.osim: key 'thigh_r': no body 'thigh_r'"));
  CHECK_FALSE(std::filesystem::exists(out));
  run = test::runCli("lump-osim --model " + test::quoted(test::opensimFile("subject01.osim")) + " --out " +
                     test::quoted(out) + " --name 'a: b'");
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Contains("--name"));
  CHECK_FALSE(std::filesystem::exists(out));
}
