// `gaitopt impact` and `gaitopt impact-map`: JSON and CSV contents, input validation, and the
// exact θ-intervals of the algebraic map against the solver; the plot script on a shipped map.
#include <catch2/catch.hpp>

#include <cstdio>
#include <regex>

#include "gaitopt/impact/impact_map.hpp"
#include "gaitopt/model/dynamics_pinned.hpp"
#include "gaitopt/model/foot_on_ground.hpp"
#include "impact/impact_test_support.hpp"
#include "test_files.hpp"
#include "test_support.hpp"

using namespace gaitopt;
using test::CliRun;
using test::runCli;

namespace {

std::string numbers(const Vec5& v) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g,%.17g,%.17g", v(0), v(1), v(2), v(3), v(4));
  return buf;
}

// The two numbers of the JSON array after "key": [
Vec2 jsonPair(const std::string& json, const std::string& key) {
  const std::regex re("\"" + key + "\": \\[([^,\\]]+), ([^\\]]+)\\]");
  std::smatch m;
  REQUIRE(std::regex_search(json, m, re));
  return Vec2(std::stod(m[1]), std::stod(m[2]));
}

}  // namespace

TEST_CASE("gaitopt impact: JSON document of the solver's result", "[impact]") {
  const Model m = test::defaultModel();
  const Vec5 q = test::walkingImpactQ(m);
  const Vec5 qd = pinnedVelocityForFoot2(m, q, Vec2(0.3, -0.5));
  for (const char* model : {"algebraic", "differential"}) {
    const CliRun run = runCli("impact --q=" + numbers(q) + " --qd=" + numbers(qd) +
                              " --mu 0.7 --model " + model);
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    ImpactOptions o;
    o.mu = 0.7;
    const ImpactResult r = solveImpactFromPinned(
        m, q, qd,
        std::string(model) == "algebraic" ? ImpactModelKind::Algebraic
                                          : ImpactModelKind::Differential,
        o);
    REQUIRE(r.solutions.size() == 1);
    for (const char* key : {"\"model\": \"", "\"V2_minus\": [", "\"status\": \"unique\"",
                            "\"solutions\": [", "\"behaviour\": {", "\"boundary\": false",
                            "\"Xd_plus\": [", "\"energy_loss\": ", "\"phases\": [", "\"tau_end\": "})
      CHECK_THAT(run.out, Catch::Matchers::Contains(key));
    CHECK_THAT(run.out, Catch::Matchers::Contains(std::string("\"model\": \"") + model + "\""));
    std::smatch mu;
    REQUIRE(std::regex_search(run.out, mu, std::regex("\"mu\": ([0-9.e+-]+)")));
    CHECK(std::stod(mu[1]) == 0.7);
    CHECK((jsonPair(run.out, "V2_minus") - Vec2(0.3, -0.5)).norm() < 1e-12);
    CHECK((jsonPair(run.out, "impulse_foot2") - r.solutions[0].impulse2).norm() < 1e-12);
    CHECK((jsonPair(run.out, "impulse_foot1") - r.solutions[0].impulse1).norm() < 1e-12);
  }
}

TEST_CASE("gaitopt impact: bad input exits 2 naming the problem", "[impact]") {
  const Model m = test::defaultModel();
  const Vec5 q = test::walkingImpactQ(m);
  const Vec5 qd = pinnedVelocityForFoot2(m, q, Vec2(0.3, -0.5));
  const std::string good_q = " --q=" + numbers(q), good_qd = " --qd=" + numbers(qd);
  const auto expectBad = [](const std::string& args, const std::string& message) {
    const CliRun run = runCli("impact " + args);
    INFO(args);
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.err, Catch::Matchers::Contains(message));
    CHECK(run.out.empty());
  };
  expectBad("--q=0.1,0.2,0.3,0.4" + good_qd + " --mu 0.7", "--q: expected 5");
  expectBad(good_q + " --qd=1,2,x,4,5 --mu 0.7", "--qd: expected 5");
  Vec5 lifted = q;
  lifted(0) += 0.01;
  expectBad(" --q=" + numbers(lifted) + good_qd + " --mu 0.7", "foot 2 height z2 = ");
  lifted(0) = q(0) + 1e-4;  // ~40 µm: beyond the projection's 1e-5 m
  expectBad(" --q=" + numbers(lifted) + good_qd + " --mu 0.7", "(|z2| <= 1e-5 m");
  expectBad(good_q + " --qd=" + numbers(-qd) + " --mu 0.7", "V2z = 0.5");
  expectBad(good_q + good_qd + " --mu -0.1", "--mu: must be in [0, 100], got -0.1");
}

TEST_CASE("gaitopt impact: six decimals of --q are projected onto the ground", "[impact]") {
  const Model m = test::defaultModel();
  const Vec5 q = test::walkingImpactQ(m);
  const Vec5 qd = pinnedVelocityForFoot2(m, q, Vec2(0.3, -0.5));
  char typed[256];  // as a user types it: six decimals, foot 2 micrometres off the ground
  std::snprintf(typed, sizeof typed, "%.6f,%.6f,%.6f,%.6f,%.6f", q(0), q(1), q(2), q(3), q(4));
  Vec5 q_typed;
  REQUIRE(std::sscanf(typed, "%lf,%lf,%lf,%lf,%lf", &q_typed(0), &q_typed(1), &q_typed(2),
                      &q_typed(3), &q_typed(4)) == 5);
  const double z2 = pinnedTerms(m, q_typed, Vec5(Vec5::Zero())).foot2(1);
  REQUIRE(std::abs(z2) > 1e-9);  // the typed configuration the old 1e-9 m rule refused
  const CliRun run =
      runCli("impact --q=" + std::string(typed) + " --qd=" + numbers(qd) + " --mu 0.7");
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.err, Catch::Matchers::Contains("--q projected onto it"));
  // The configuration used is the projection, with foot 2 on the ground.
  const std::regex re("\"q\": \\[([^\\]]+)\\]");
  std::smatch match;
  REQUIRE(std::regex_search(run.out, match, re));
  Vec5 used;
  REQUIRE(std::sscanf(match[1].str().c_str(), "%lf, %lf, %lf, %lf, %lf", &used(0), &used(1),
                      &used(2), &used(3), &used(4)) == 5);
  CHECK((used - projectFoot2OnGround(m, q_typed).q).norm() < 1e-14);
  CHECK(std::abs(pinnedTerms(m, used, Vec5(Vec5::Zero())).foot2(1)) < 1e-12);
  CHECK((used - q_typed).cwiseAbs().maxCoeff() < 1e-5);
}

TEST_CASE("gaitopt impact-map: exact theta-intervals agree with the solver", "[impact]") {
  const Model m = test::defaultModel();
  const Vec5 q = test::legsSpreadQ(m);
  const std::vector<ThetaInterval> iv =
      algebraicThetaIntervals(m, q, 0.6, -179.0 * M_PI / 180.0, -1.0 * M_PI / 180.0);
  REQUIRE(!iv.empty());
  // Each interval end is a zone boundary: there the solver flags the behaviour as boundary
  // (or it vanishes just past it); strictly inside, the solver finds exactly that behaviour.
  for (const ThetaInterval& i : iv) {
    for (double f : {0.25, 0.5, 0.75}) {
      const double th = i.begin + f * (i.end - i.begin);
      ImpactOptions o;
      o.mu = 0.6;
      const ImpactResult r =
          solveImpactFromPinned(m, q, pinnedVelocityForFoot2(m, q, Vec2(std::cos(th), std::sin(th))),
                                ImpactModelKind::Algebraic, o);
      bool found = false;
      for (const ImpactSolution& s : r.solutions) found = found || s.behaviour == i.behaviour;
      INFO(behaviourLabel(i.behaviour) << " at " << th * 180.0 / M_PI);
      CHECK(found);
    }
  }
  test::ScratchDir dir("impact_map");
  const std::string out = dir.fresh("map");
  const CliRun run = runCli("impact-map --q=" + numbers(q) +
                            " --mu-range 0:1:3 --theta-range=-170:-10:5 --out " + test::quoted(out));
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  const std::string csv = test::readFile(out + "/map.csv");
  CHECK(csv.rfind("theta_deg,mu,behaviour,n_solutions,status\n", 0) == 0);
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 3 * 5);
  CHECK_THAT(csv, Catch::Matchers::Contains("\n-90,0.5,"));
  const CliRun bad = runCli("impact-map --q=" + numbers(q) + " --mu-range 0:1 --out " +
                            test::quoted(dir.fresh("bad")));
  CHECK(bad.exit_code == 2);
  CHECK_THAT(bad.err, Catch::Matchers::Contains("--mu-range: expected a:b:n"));
}

TEST_CASE("impact_map.py draws the shipped sample map", "[impact]") {
  test::ScratchDir dir("impact_plot");
  const std::string png = dir.fresh("map") + ".png";
  const std::string cmd = "/usr/bin/python3 " + test::quoted(test::sourcePath("scripts/plot/impact_map.py")) +
                          " " + test::quoted(test::sourcePath("tests/impact/data/impact_map_legs_spread.csv")) +
                          " " + test::quoted(png) + " >/dev/null 2>&1";
  REQUIRE(std::system(cmd.c_str()) == 0);
  const std::string bytes = test::readFile(png);
  REQUIRE(bytes.size() > 10000);
  CHECK(bytes.substr(1, 3) == "PNG");
  const std::string bad = dir.write("theta,mu\n1,2\n");
  const std::string bad_cmd = "/usr/bin/python3 " + test::quoted(test::sourcePath("scripts/plot/impact_map.py")) +
                              " " + test::quoted(bad) + " " + test::quoted(png + "2") + " >/dev/null 2>&1";
  const int status = std::system(bad_cmd.c_str());
  CHECK(WEXITSTATUS(status) == 2);
}
