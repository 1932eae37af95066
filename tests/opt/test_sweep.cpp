// Speed sweeps: the --speeds and --shard syntax, contiguous chunks, continuation on the default
// robot (one chain, two threaded chains, shards), sweep.csv merging. Three speeds only, to keep
// the runtime small.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "gaitopt/opt/initial_guess.hpp"
#include "gaitopt/io/csv_table.hpp"
#include "gaitopt/io/optimize_config.hpp"
#include "gaitopt/io/sweep_file.hpp"
#include "test_files.hpp"
#include "test_gait_support.hpp"
#include "test_sweep_csv.hpp"

using Catch::Matchers::Contains;
using gaitopt::OptimizationRequest;
using gaitopt::parseShard;
using gaitopt::parseSpeedRange;
using gaitopt::SweepPoint;
using gaitopt::SweepSettings;
using gaitopt::test::firstField;
using gaitopt::test::lines;

namespace {

const gaitopt::GaitEvaluator& evaluator() {
  // The default options (dry friction): the verdict then has no robot friction to add.
  static const gaitopt::GaitEvaluator ev =
      gaitopt::test::defaultGaitEvaluator(gaitopt::GaitOptions{});
  return ev;
}

OptimizationRequest baseRequest() {
  OptimizationRequest r;
  r.initial = gaitopt::defaultInitialGuess(evaluator().model(), std::nullopt);
  r.solver.print_every = 0;
  return r;
}

bool sameBits(const gaitopt::GaitParameters& a, const gaitopt::GaitParameters& b) {
  for (int i = 0; i < gaitopt::kNumGaitParameters; ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(double)) != 0) return false;
  return true;
}

}  // namespace

TEST_CASE("parseSpeedRange: inclusive ranges, rounded values", "[sweep]") {
  CHECK(parseSpeedRange("0.4:0.6:0.1") == std::vector<double>{0.4, 0.5, 0.6});
  const std::vector<double> v = parseSpeedRange("0.2:1.0:0.05");
  REQUIRE(v.size() == 17);
  CHECK(v.front() == 0.2);
  CHECK(v[2] == 0.3);
  CHECK(v.back() == 1.0);
  CHECK(parseSpeedRange("0.2:1:0.3") == std::vector<double>{0.2, 0.5, 0.8});
  CHECK(parseSpeedRange("0.5:0.5:0.1") == std::vector<double>{0.5});
  CHECK(parseSpeedRange("1e-1:3e-1:1e-1") == std::vector<double>{0.1, 0.2, 0.3});
}

TEST_CASE("parseSpeedRange rejects malformed ranges with a clear message", "[sweep]") {
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(parseSpeedRange(""), Contains("expected start:stop:step"));
  CHECK_THROWS_WITH(parseSpeedRange("0.2:1.0"), Contains("expected start:stop:step"));
  CHECK_THROWS_WITH(parseSpeedRange("0.2:1.0:0.1:2"), Contains("expected start:stop:step"));
  CHECK_THROWS_WITH(parseSpeedRange("a:1.0:0.1"), Contains("start 'a' is not a finite number"));
  CHECK_THROWS_WITH(parseSpeedRange("0.2:1.0x:0.1"), Contains("stop '1.0x'"));
  CHECK_THROWS_WITH(parseSpeedRange("0.2::0.1"), Contains("stop ''"));
  CHECK_THROWS_WITH(parseSpeedRange("0.2:inf:0.1"), Contains("not a finite number"));
  CHECK_THROWS_WITH(parseSpeedRange("0:1:0.1"), Contains("start must be > 0"));
  CHECK_THROWS_WITH(parseSpeedRange("-0.2:1:0.1"), Contains("start must be > 0"));
  CHECK_THROWS_WITH(parseSpeedRange("1.0:0.2:0.1"), Contains("stop must be >= start"));
  CHECK_THROWS_WITH(parseSpeedRange("0.2:1:0"), Contains("step must be > 0"));
  CHECK_THROWS_WITH(parseSpeedRange("0.2:1:-0.1"), Contains("step must be > 0"));
  CHECK_THROWS_WITH(parseSpeedRange("0.1:10:0.0001"), Contains("more than 10000 speeds"));
  CHECK_THROWS_AS(parseSpeedRange("x"), std::invalid_argument);
}

TEST_CASE("parseShard and splitContiguous", "[sweep]") {
  CHECK(parseShard("0/2").index == 0);
  CHECK(parseShard("1/2").index == 1);
  CHECK(parseShard("1/2").count == 2);
  CHECK_THROWS_WITH(parseShard("2/2"), Contains("index must be < n"));
  CHECK_THROWS_WITH(parseShard("0/0"), Contains("n must be >= 1"));
  CHECK_THROWS_WITH(parseShard("-1/2"), Contains("not a non-negative integer"));
  CHECK_THROWS_WITH(parseShard("1"), Contains("expected i/n"));
  CHECK_THROWS_WITH(parseShard("a/2"), Contains("not a non-negative integer"));

  const std::vector<double> s = parseSpeedRange("0.2:1.0:0.1");
  const auto chunks = gaitopt::splitContiguous(s, 2);
  REQUIRE(chunks.size() == 2);
  CHECK(chunks[0] == std::vector<double>{0.2, 0.3, 0.4, 0.5});
  CHECK(chunks[1] == std::vector<double>{0.6, 0.7, 0.8, 0.9, 1.0});
  std::vector<double> joined;
  for (const auto& c : gaitopt::splitContiguous(s, 4)) {
    CHECK(c.size() >= 2);
    joined.insert(joined.end(), c.begin(), c.end());
  }
  CHECK(joined == s);
  CHECK_THROWS_WITH(gaitopt::splitContiguous(s, 10), Contains("need 1 <= chunks <= speeds"));
  CHECK_THROWS_WITH(gaitopt::sortedSpeeds({0.5, 0.4, 0.5}), Contains("appears twice"));
  CHECK(gaitopt::sortedSpeeds({0.6, 0.4}) == std::vector<double>{0.4, 0.6});
}

TEST_CASE("sweepSpeeds on the default robot: one chain", "[sweep]") {
  const std::vector<double> speeds = parseSpeedRange("0.4:0.6:0.1");
  std::vector<int> done;
  int free_reports = 0;
  const std::vector<SweepPoint> r = gaitopt::sweepSpeeds(
      evaluator(), baseRequest(), speeds, SweepSettings{}, [&](const gaitopt::SweepProgress& p) {
        if (p.free_speed) {
          ++free_reports;
          CHECK(p.point.result.status == gaitopt::OptimizationStatus::Optimal);
        } else {
          done.push_back(p.done);
          CHECK(p.total == 3);
        }
      });
  CHECK(free_reports == 1);
  CHECK(done == std::vector<int>{1, 2, 3});
  REQUIRE(r.size() == 3);
  int cold = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    INFO("speed " << r[i].speed);
    CHECK(r[i].speed == speeds[i]);
    CHECK(r[i].result.status == gaitopt::OptimizationStatus::Optimal);
    CHECK(std::abs(r[i].result.evaluation.speed - speeds[i]) <= 1e-6);
    CHECK(r[i].attempts >= 1);
    if (!r[i].warm_started) ++cold;
  }
  // The free-speed optimum is slower than 0.4 m/s: the chain starts there and walks up.
  CHECK(cold == 1);
  CHECK_FALSE(r[0].warm_started);
  CHECK(r[1].warm_started);
  CHECK(r[1].from_speed == 0.4);
  CHECK(r[2].warm_started);
  CHECK(r[2].from_speed == 0.5);
}

// The 10-speed library on configs/default.yaml. 0.85 m/s: the walk's attempt from the 0.65 m/s
// optimum (0.75 m/s has none yet; one restart) ends without an optimum; resumed from its last
// point with the configured restarts, it ends optimal (its retries from the elastic problem's
// step and from the default initial guess had ended `failed`). 1.05 m/s: the knee's joint
// limit certified.
TEST_CASE("sweepSpeeds: a walk's attempt without an optimum resumes with the configured restarts",
          "[sweep]") {
  const gaitopt::OptimizeConfig config =
      gaitopt::loadOptimizeConfig(gaitopt::test::sourcePath("configs/default.yaml"));
  const gaitopt::GaitEvaluator ev(config.robot, config.options, config.model_options);
  OptimizationRequest base =
      gaitopt::optimizationRequest(config, gaitopt::configuredInitialGuess(config, ev.model()));
  base.solver.print_every = 0;
  const std::vector<SweepPoint> r =
      gaitopt::sweepSpeeds(ev, base, parseSpeedRange("0.15:1.05:0.1"), SweepSettings{});
  REQUIRE(r.size() == 10);
  int optimal = 0;
  for (const SweepPoint& p : r) optimal += gaitopt::isOptimal(p.result);
  CHECK(optimal == 8);  // measured; 7 without the resumed attempt
  const SweepPoint& v085 = r[7];
  INFO("0.85 m/s: " << v085.result.status << ", " << v085.attempts << " attempts");
  CHECK(v085.result.status == gaitopt::OptimizationStatus::Optimal);
  CHECK(v085.attempts == 2);
  CHECK(v085.warm_started);
  CHECK(v085.from_speed == 0.65);
  CHECK(v085.result.evaluation.C_Gamma == Approx(19661.75).epsilon(1e-3));
  const SweepPoint& v105 = r[9];
  CHECK(v105.result.status == gaitopt::OptimizationStatus::Infeasible);
  REQUIRE(v105.certificate);
  CHECK(v105.certificate->infeasible());
  REQUIRE_FALSE(v105.certificate->blocking.empty());
  CHECK_THAT(v105.certificate->blocking.front().name, Contains("joint_limits_ss knee 2 upper"));
}

TEST_CASE("sweepSpeeds: two threaded chains are deterministic and equal the two shards",
          "[sweep]") {
  const std::vector<double> speeds = parseSpeedRange("0.4:0.6:0.1");
  SweepSettings two;
  two.jobs = 2;
  const std::vector<SweepPoint> a = gaitopt::sweepSpeeds(evaluator(), baseRequest(), speeds, two);
  const std::vector<SweepPoint> b = gaitopt::sweepSpeeds(evaluator(), baseRequest(), speeds, two);
  REQUIRE(a.size() == 3);
  REQUIRE(b.size() == 3);
  for (std::size_t i = 0; i < a.size(); ++i) {
    INFO("speed " << a[i].speed);
    CHECK(a[i].speed == speeds[i]);
    CHECK(a[i].result.status == gaitopt::OptimizationStatus::Optimal);
    CHECK(std::abs(a[i].result.evaluation.speed - speeds[i]) <= 1e-6);
    CHECK(sameBits(a[i].result.parameters, b[i].result.parameters));
    CHECK(a[i].result.evaluation.C_Gamma == b[i].result.evaluation.C_Gamma);
    CHECK(a[i].attempts == b[i].attempts);
    CHECK(a[i].total_iterations == b[i].total_iterations);
  }

  // Shards 0/2 and 1/2 (0-based) cover the list exactly once, and each equals its chain.
  std::vector<SweepPoint> shards;
  for (int i = 0; i < 2; ++i) {
    SweepSettings s;
    s.sharded = true;
    s.shard = {i, 2};
    const auto part = gaitopt::sweepSpeeds(evaluator(), baseRequest(), speeds, s);
    shards.insert(shards.end(), part.begin(), part.end());
  }
  REQUIRE(shards.size() == speeds.size());
  for (std::size_t i = 0; i < shards.size(); ++i) {
    INFO("speed " << speeds[i]);
    CHECK(shards[i].speed == speeds[i]);
    CHECK(sameBits(shards[i].result.parameters, a[i].result.parameters));
  }
  CHECK(gaitopt::sweepRunSpeeds(speeds, [] {
          SweepSettings s;
          s.sharded = true;
          s.shard = {0, 2};
          return s;
        }()) == std::vector<double>{0.4});
  SweepSettings too_many;
  too_many.sharded = true;
  too_many.shard = {0, 4};
  CHECK_THROWS_WITH(gaitopt::sweepRunSpeeds(speeds, too_many),
                    Contains("exceeds the number of speeds"));
}

TEST_CASE("mergeSweepCsvs sorts rows and rejects duplicates and foreign headers", "[sweep]") {
  const std::string h = std::string(gaitopt::kSweepCsvHeader) + "\n";
  const std::string a = h + "0.5,optimal,1,2,3,4,0.005,0.3,0.5,0.04,10,0.1,,,,,\n";
  const std::string b = h + "0.40000000000000002,optimal,1,2,3,4,0.005,0.3,0.5,0.04,10,0.1,,,,,\n" +
                        "0.6,infeasible,,,,,,0.3,,0.04,10,0.1,,,,,\n";
  const std::vector<std::string> merged = lines(gaitopt::mergeSweepCsvs({a, b}, {"a", "b"}));
  REQUIRE(merged.size() == 4);
  CHECK(merged[0] == gaitopt::kSweepCsvHeader);
  CHECK(firstField(merged[1]) == 0.4);
  CHECK(firstField(merged[2]) == 0.5);
  CHECK(firstField(merged[3]) == 0.6);
  CHECK_THROWS_WITH(gaitopt::mergeSweepCsvs({a, a}, {"a", "a2"}), Contains("appears twice"));
  CHECK_THROWS_WITH(gaitopt::mergeSweepCsvs({a, "speed,status\n"}, {"a", "x"}),
                    Contains("x: header"));
  CHECK_THROWS_WITH(gaitopt::mergeSweepCsvs({h + "0.5,optimal\n"}, {"y"}), Contains("y:2"));
  CHECK(gaitopt::sweepFolderName(0.5, 3) == "v0.500");
  CHECK(gaitopt::sweepFolderDecimals({0.4, 0.5}) == 3);
  CHECK(gaitopt::sweepFolderDecimals({0.5, 0.5001}) == 4);
}

TEST_CASE("sweep.csv: the elastic problem's columns and progress text", "[sweep]") {
  const std::vector<std::string> header = gaitopt::splitFields(gaitopt::kSweepCsvHeader);
  REQUIRE(header.size() == 17);
  CHECK(std::vector<std::string>(header.end() - 5, header.end()) ==
        std::vector<std::string>{"min_violation", "blocking_constraint", "blocking_value",
                                 "blocking_unit", "blocking_multiplier"});
  SweepPoint p;
  p.speed = 1.05;
  p.attempts = 1;
  p.result.status = gaitopt::OptimizationStatus::Infeasible;
  p.result.parameters = gaitopt::defaultInitialGuess(evaluator().model(), 1.05);
  p.result.evaluation = evaluator().evaluate(p.result.parameters);
  // Without the elastic problem: five empty fields, no text.
  std::vector<std::string> row = gaitopt::splitFields(gaitopt::sweepCsvRow(evaluator(), p));
  REQUIRE(row.size() == 17);
  for (std::size_t c = 12; c < 17; ++c) CHECK(row[c].empty());
  CHECK(gaitopt::sweepEvidenceText(p).empty());

  // Rows met: s* only, "not shown infeasible".
  gaitopt::InfeasibilityCertificate c;
  c.min_violation = -2e-5;
  p.certificate = c;
  row = gaitopt::splitFields(gaitopt::sweepCsvRow(evaluator(), p));
  CHECK(std::stod(row[12]) == -2e-5);
  CHECK(row[13].empty());
  CHECK_THAT(gaitopt::sweepEvidenceText(p), Contains("not shown infeasible"));

  // A certificate: its largest share.
  c.converged = true;
  c.min_violation = 0.025;
  c.blocking = {{0, "joint_limits_ss knee 2 upper at SS node 16", 0.353, 0.025, "rad"},
                {1, "clearance at SS node 15", 0.2, 0.001, "m"}};
  p.certificate = c;
  const std::string text = gaitopt::sweepCsvRow(evaluator(), p);
  row = gaitopt::splitFields(text);
  CHECK(row[13] == "joint_limits_ss knee 2 upper at SS node 16");
  CHECK(std::stod(row[14]) == 0.025);
  CHECK(row[15] == "rad");
  CHECK(std::stod(row[16]) == 0.353);
  CHECK(gaitopt::sweepEvidenceText(p) ==
        "blocked by joint_limits_ss knee 2 upper at SS node 16 (+0.025 rad, multiplier 0.353)  ");
  // The row reads back; a name with a quote or a negative multiplier does not.
  const std::string h = std::string(gaitopt::kSweepCsvHeader) + "\n";
  CHECK(lines(gaitopt::mergeSweepCsvs({h + text + "\n"}, {"s"}))[1] == text);
  std::string quoted = text;
  quoted.replace(quoted.find("knee 2"), 6, "knee\"2");
  CHECK_THROWS_WITH(gaitopt::mergeSweepCsvs({h + quoted + "\n"}, {"s"}),
                    Contains("column blocking_constraint"));
  std::string negative = text;
  negative.replace(negative.rfind(",0.35"), 5, ",-0.35");
  CHECK_THROWS_WITH(gaitopt::mergeSweepCsvs({h + negative + "\n"}, {"s"}),
                    Contains("column blocking_multiplier"));
}
