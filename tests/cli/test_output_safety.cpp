// Output safety of every writing command (docs/reliability.md): bad output locations exit 2
// naming the problem with nothing written or overwritten anywhere; planted links at final or
// staging names are never followed; stale staging folders of killed runs are removed by the
// next run; a run killed at any time leaves the old complete result or the new one (every
// command that writes more than one file, and synth's one file holding data and truth).
#include <catch2/catch.hpp>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "gaitopt/io/csv_table.hpp"
#include "test_files.hpp"
#include "test_opensim_data.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using namespace gaitopt::test;

namespace {

const std::string kGait = sourcePath("configs/gait/default_step.yaml");
const std::string kRobot = sourcePath("configs/robot/rabbit_miossec.yaml");

ScratchDir& scratch() {
  static ScratchDir dir("output_safety", "input");
  return dir;
}

// Every entry under `dir`, hidden ones included, with its content ("-> target" for a link,
// "/" for a directory): any write, removal or new file shows up as a difference. A file
// `dir` is the one entry "".
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> entries;
  if (fs::is_regular_file(dir)) return {{"", readFile(dir.string())}};
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
       ++it) {
    const fs::path rel = fs::relative(it->path(), dir);
    if (it->is_symlink())
      entries[rel.string()] = "-> " + fs::read_symlink(it->path()).string();
    else if (it->is_directory())
      entries[rel.string()] = "/";
    else
      entries[rel.string()] = readFile(it->path().string());
  }
  return entries;
}

// A sandbox with a precious file, a folder of someone else's files, a copy of the robot file
// and a run's previous output; runs start in it, so `.` and relative names point into it.
struct Sandbox {
  fs::path dir = scratch().fresh("sandbox");
  Sandbox() {
    fs::create_directories(dir / "foreign");
    fs::create_directories(dir / "previous");
    std::ofstream(dir / "precious.txt") << "precious\n";
    std::ofstream(dir / "bad.yaml") << "a: [1, 2\n";  // a YAML flow never closed
    std::ofstream(dir / "foreign" / "notes.txt") << "mine\n";
    std::ofstream(dir / "previous" / "extended_robot.yaml") << readFile(kRobot);
    fs::copy_file(kRobot, dir / "robot.yaml");
  }
  // Runs gaitopt `args` with the sandbox as working directory.
  CliRun run(const std::string& args) const {
    return runCli("--version >/dev/null; cd " + quoted(dir.string()) + " && " +
                  quoted(GAITOPT_CLI) + " " + args);
  }
};

// Sets the modification time of `path` (not of a link's target) to an hour ago.
void backdate(const fs::path& path) {
  const timespec hour_ago[2] = {{time(nullptr) - 3600, 0}, {time(nullptr) - 3600, 0}};
  REQUIRE(::utimensat(AT_FDCWD, path.c_str(), hour_ago, AT_SYMLINK_NOFOLLOW) == 0);
}

// Hidden staging folders beside the entries of `dir`.
std::vector<std::string> stagingEntries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".gaitopt-") != std::string::npos)
      names.push_back(e.path().filename().string());
  return names;
}

}  // namespace

TEST_CASE("output safety: bad output locations of every command", "[reliability][cli]") {
  const std::string gait = quoted(kGait), robot = quoted(kRobot);
  const std::string opensim = "import-opensim --ik " + quoted(opensimIk()) + " --grf " +
                              quoted(opensimGrf()) + " --trunk model --robot " +
                              quoted(sourcePath("configs/robot/human_subject01.yaml")) + " ";
  const std::string simulate = "simulate --steps 1 --gait " + gait;
  const std::string stability = "stability --gait " + gait;
  const std::string diagnose = "diagnose --robot " + robot + " --data " +
                               quoted(sourcePath("fuzz/seeds/measured.csv"));
  const std::string impact_map = "impact-map --robot " + robot +
                                 " --q=-0.4,-2.8415926535897933,-3.3415926535897933,"
                                 "0.50741499796637735,-2.7987334866164235";
  const std::string merge = "sweep-merge " + quoted(sourcePath("tests/data/sample_sweep"));
  const std::string synth = "synth --steps 3 --robot " + robot + " --gait " + gait;
  const std::string model = "export-model --format urdf --robot robot.yaml";
  const std::string exporter = "export --steps 1 --gait " + gait;
  const std::string plot = "plot stick " + quoted(sourcePath("tests/data/sample_run"));
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      // Directory results: `/`, `.`, a file, someone else's folder, a folder holding an input.
      {simulate + " --out /", "is the current directory or contains it"},
      {simulate + " --out .", "is the current directory or contains it"},
      {simulate + " --out precious.txt", "--out 'precious.txt' exists and is not a directory"},
      {simulate + " --out foreign", "holds 'notes.txt', which gaitopt did not write"},
      {stability + " --out /", "is the current directory or contains it"},
      {stability + " --out foreign", "holds 'notes.txt'"},
      {diagnose + " --out .", "is the current directory or contains it"},
      {diagnose + " --out foreign", "holds 'notes.txt'"},
      {"diagnose --robot previous/extended_robot.yaml --data " +
           quoted(sourcePath("fuzz/seeds/measured.csv")) + " --out previous",
       "--out 'previous' holds the input --robot 'previous/extended_robot.yaml'"},
      {"evaluate --gait " + gait + " --out /", "is the current directory or contains it"},
      {impact_map + " --out /", "is the current directory or contains it"},
      {impact_map + " --out precious.txt", "exists and is not a directory"},
      {impact_map + " --out foreign", "holds 'notes.txt'"},
      {merge + " --out " + quoted(sourcePath("tests/data/sample_sweep")),
       "names the input SHARD_DIR"},
      // File results: `/`, `.`, a directory, a missing folder, an input, another output.
      {model + " --out /", "--out '/' is a directory, a file is expected"},
      {model + " --out .", "--out '.' is a directory, a file is expected"},
      {model + " --out foreign/", "is a directory, a file is expected"},
      {model + " --out missing/robot.urdf", "its directory 'missing' does not exist"},
      {model + " --out robot.yaml", "--out 'robot.yaml' names the input --robot 'robot.yaml'"},
      {model + " --out ./robot.yaml", "names the input --robot"},
      {exporter + " --out " + gait, "names the input --gait"},
      {exporter + " --out foreign", "is a directory, a file is expected"},
      {synth + " --out " + robot, "names the input --robot"},
      {synth + " --out .", "is a directory, a file is expected"},
      {opensim + "--out " + quoted(opensimIk()), "names the input --ik"},
      {opensim + "--result " + quoted(opensimIk()), "exists and is not a directory"},
      {opensim + "--out foreign/", "is a directory, a file is expected"},
      {plot + " --out /x/y/z.png", "its directory '/x/y' does not exist"},
  };
  for (const Case& c : cases) {
    const Sandbox box;
    const auto before = snapshot(box.dir);
    const CliRun run = box.run(c.args);
    INFO(c.args << "\n" << run.err);
    CHECK(run.exit_code == 2);
    CHECK_THAT(run.err, Contains(c.message));
    CHECK(snapshot(box.dir) == before);  // nothing written, removed or left behind
  }
}

TEST_CASE("output safety: every command refuses a bad option, a bad file and a bad --out",
          "[reliability][cli]") {
  // With the cases of the table above and of test_option_syntax.cpp, each writing command has
  // a bad option value, a bad input file, --out naming an input, and --out `/` or `.`.
  const std::string gait = quoted(kGait), robot = quoted(kRobot);
  const std::string config = quoted(sourcePath("configs/default.yaml"));
  const std::string run = quoted(sourcePath("tests/data/sample_run"));
  const std::string q = " --q=-0.4,-2.8415926535897933,-3.3415926535897933,0.50741499796637735,"
                        "-2.7987334866164235";
  const std::string evaluate = "evaluate --gait " + gait;
  const std::string optimize = "optimize --config " + config;
  const std::string sweep = "sweep --speeds 0.5:0.5:0.1 --config ";
  const std::string merge = "sweep-merge " + quoted(sourcePath("tests/data/sample_sweep"));
  const std::string exporter = "export --steps 1 --gait " + gait;
  const std::string plot = "plot stick " + run;
  const std::string invalid_yaml = "bad.yaml:2: invalid YAML";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {evaluate + " --sample-rate nan --out o", "--sample-rate: not a finite number: 'nan'"},
      {"evaluate --gait bad.yaml --out o", invalid_yaml},
      {evaluate + " --out " + gait, "exists and is not a directory"},
      {optimize + " --speed nan --out o", "--speed: not a finite number: 'nan'"},
      {"optimize --config bad.yaml --out o", invalid_yaml},
      {optimize + " --out " + config, "exists and is not a directory"},
      {optimize + " --out /", "is the current directory or contains it"},
      {sweep + config + " --jobs 0x2 --out o", "--jobs: '0x2' is not a whole decimal number"},
      {sweep + "bad.yaml --out o", invalid_yaml},
      {sweep + config + " --out " + config, "exists and is not a directory"},
      {sweep + config + " --out .", "is the current directory or contains it"},
      {merge + " --out=", "--out=: empty value after '='"},
      {"sweep-merge foreign --out o", "'foreign/sweep.csv' is missing or not a regular file"},
      {merge + " --out /", "--out '/' is the current directory or contains it"},
      {merge + " --out .", "--out '.' is the current directory or contains it"},
      {merge + " --out precious.txt", "--out 'precious.txt' exists and is not a directory"},
      {"simulate --gait bad.yaml --out o", invalid_yaml},
      {"simulate --gait " + gait + " --out " + gait, "exists and is not a directory"},
      {"stability --gait bad.yaml --out o", invalid_yaml},
      {"stability --gait " + gait + " --out " + gait, "exists and is not a directory"},
      {"impact-map --robot bad.yaml --out o" + q, invalid_yaml},
      {"impact-map --robot robot.yaml --out robot.yaml" + q, "exists and is not a directory"},
      {"diagnose --holdout 0x3 --robot " + robot + " --data bad.yaml --out o",
       "--holdout: '0x3' is not a whole decimal number"},
      {"diagnose --robot " + robot + " --data bad.yaml --out o",
       "bad.yaml:1: column 'a: [1': unknown column"},
      {"synth --steps 3 --robot bad.yaml --gait " + gait + " --out o.csv", invalid_yaml},
      {"synth --steps 3 --robot " + robot + " --gait bad.yaml --out o.csv", invalid_yaml},
      {"export --gait bad.yaml --out o.csv", invalid_yaml},
      {exporter + " --out .", "--out '.' is a directory, a file is expected"},
      {exporter + " --out /", "--out '/' is a directory, a file is expected"},
      {"export-model --format urdf --robot bad.yaml --out o.urdf", invalid_yaml},
      {plot + " --out o.txt", "must end in .png or .svg"},
      {"plot stick foreign --out o.png", "foreign: no summary.json"},
      {plot + " --out " + quoted(sourcePath("tests/data/sample_run/summary.json")),
       "must end in .png or .svg"},
      {plot + " --out /", "must end in .png or .svg"},
  };
  const auto sample_run = snapshot(sourcePath("tests/data/sample_run"));
  for (const auto& [args, message] : cases) {
    const Sandbox box;
    const auto before = snapshot(box.dir);
    const CliRun r = box.run(args);
    INFO(args << "\n" << r.err);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.err, Contains(message));
    CHECK(snapshot(box.dir) == before);  // nothing written, removed or left behind
  }
  CHECK(snapshot(sourcePath("tests/data/sample_run")) == sample_run);
}

TEST_CASE("output safety: planted links at final and staging names are not followed",
          "[reliability][cli]") {
  const Sandbox box;
  const fs::path precious = box.dir / "precious.txt";
  // A link at the final name of a file result is replaced by the file.
  fs::create_symlink(precious, box.dir / "robot.urdf");
  // A link at a staging name (hidden, beside --out), old enough to count as stale, pointing at
  // a folder: the stale-folder cleanup must neither follow nor remove it.
  fs::create_symlink(box.dir / "foreign", box.dir / ".robot.urdf.gaitopt-abc123");
  backdate(box.dir / ".robot.urdf.gaitopt-abc123");
  const CliRun run = box.run("export-model --format urdf --robot robot.yaml --out robot.urdf");
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  CHECK(readFile(precious.string()) == "precious\n");
  CHECK_FALSE(fs::is_symlink(box.dir / "robot.urdf"));
  CHECK_THAT(readFile((box.dir / "robot.urdf").string()), Contains("<robot"));
  CHECK(readFile((box.dir / "foreign" / "notes.txt").string()) == "mine\n");
  CHECK(fs::is_symlink(box.dir / ".robot.urdf.gaitopt-abc123"));

  // plot: the script draws into the staging folder; the link at the figure's name is replaced.
  fs::create_symlink(precious, box.dir / "stick.png");
  const CliRun plot =
      box.run("plot stick " + quoted(sourcePath("tests/data/sample_run")) + " --out stick.png");
  INFO(plot.err);
  REQUIRE(plot.exit_code == 0);
  CHECK_THAT(plot.out, Contains("wrote stick.png"));
  CHECK(readFile(precious.string()) == "precious\n");
  CHECK_FALSE(fs::is_symlink(box.dir / "stick.png"));
  CHECK(fs::file_size(box.dir / "stick.png") > 1000);
  CHECK(stagingEntries(box.dir) == std::vector<std::string>{".robot.urdf.gaitopt-abc123"});

  // A link at an output name inside a directory result is replaced, not followed.
  fs::create_directories(box.dir / "walk");
  fs::create_symlink(precious, box.dir / "walk" / "steps.csv");
  const CliRun walk = box.run("simulate --steps 1 --gait " + quoted(kGait) + " --out walk");
  INFO(walk.err);
  REQUIRE(walk.exit_code == 0);
  CHECK(readFile(precious.string()) == "precious\n");
  CHECK_FALSE(fs::is_symlink(box.dir / "walk" / "steps.csv"));
  CHECK_THAT(readFile((box.dir / "walk" / "steps.csv").string()), Contains("step"));
}

TEST_CASE("output safety: stale staging folders of ended runs are removed, live ones kept",
          "[reliability][cli]") {
  const Sandbox box;
  const auto staging = [&](const std::string& suffix) {
    const fs::path p = box.dir / (".robot.urdf.gaitopt-" + suffix);
    fs::create_directories(p);
    std::ofstream(p / "robot.urdf") << "partial";
    return p;
  };
  const fs::path stale = staging("old123"), old_format = staging("abcdefghij"),
                 fresh = staging("new123"), locked = staging("lck123");
  backdate(stale);
  backdate(old_format);
  backdate(locked);
  // A live run holds its folder's lock: this process plays it.
  const int fd = ::open(locked.c_str(), O_RDONLY | O_DIRECTORY);
  REQUIRE(fd >= 0);
  REQUIRE(::flock(fd, LOCK_EX) == 0);
  const CliRun run = box.run("export-model --format urdf --robot robot.yaml --out robot.urdf");
  ::close(fd);
  INFO(run.err);
  REQUIRE(run.exit_code == 0);
  CHECK_FALSE(fs::exists(stale));       // unlocked, an hour old: its run has ended
  CHECK_FALSE(fs::exists(old_format));  // the 10-character names of earlier versions too
  CHECK(fs::exists(fresh));             // too young: a run may be between mkdtemp and flock
  CHECK(fs::exists(locked));            // locked: its run is alive
}

TEST_CASE("output safety: a killed run leaves the old or the new result, never a mix",
          "[reliability][cli]") {
  const Sandbox box;
  // `old_run` then `new_run` write the same files with other content into OUT; `new_run` is
  // killed (SIGKILL) after each delay: OUT must then hold the complete old or the complete new
  // result (its complete reference run), whatever the moment.
  // `out` names the result (a directory, or a file); its files compare without their wall
  // times (the lines naming one, sweep.csv's wall_time_s column), the one part of a result
  // that differs between identical runs.
  const auto requireOldOrNew = [&](const std::string& old_run, const std::string& new_run,
                                   const std::vector<std::string>& delays,
                                   const std::string& out = "walk",
                                   const std::string& option = "--out") {
    const auto result = [&](const std::string& name) {
      auto entries = snapshot(box.dir / name);
      for (auto& [path, content] : entries) {
        std::istringstream lines(content);
        content.clear();
        const bool sweep_csv = path.size() >= 9 && path.substr(path.size() - 9) == "sweep.csv";
        int wall_column = -1;
        for (std::string line; std::getline(lines, line);) {
          if (line.find("wall_time_s\"") != std::string::npos) continue;
          if (!sweep_csv) {
            content += line + "\n";
            continue;
          }
          std::vector<std::string> fields = gaitopt::splitFields(line);
          if (wall_column < 0)
            wall_column = static_cast<int>(
                std::find(fields.begin(), fields.end(), "wall_time_s") - fields.begin());
          if (wall_column < static_cast<int>(fields.size()))
            fields.erase(fields.begin() + wall_column);
          for (const std::string& f : fields) content += f + ",";
          content += "\n";
        }
      }
      return entries;
    };
    REQUIRE(box.run(new_run + " " + option + " reference").exit_code == 0);
    const auto reference = result("reference");
    REQUIRE(box.run(old_run + " " + option + " " + out).exit_code == 0);
    const auto old = result(out);
    REQUIRE(old != reference);
    int killed = 0;
    for (const std::string& delay : delays) {
      const CliRun run = box.run("--version >/dev/null; timeout -s KILL " + delay + " " +
                                 quoted(GAITOPT_CLI) + " " + new_run + " " + option + " " + out);
      INFO(new_run << ": killed after " << delay << " s, exit " << run.exit_code);
      killed += run.exit_code == 137;
      const auto now = result(out);
      CHECK((now == old || now == reference));
      if (now == reference) REQUIRE(box.run(old_run + " " + option + " " + out).exit_code == 0);
    }
    INFO(new_run << ": no delay killed it");
    CHECK(killed > 0);  // at least one run was really killed mid-way
    // A killed run leaves its staging folder; the next run removes it once it is stale.
    for (const std::string& name : stagingEntries(box.dir)) backdate(box.dir / name);
    REQUIRE(box.run(old_run + " " + option + " " + out).exit_code == 0);
    CHECK(stagingEntries(box.dir).empty());
    fs::remove_all(box.dir / "reference");
    fs::remove_all(box.dir / out);
  };
  // simulate: 4 files, about 0.5 s for 30 steps, written at the end.
  const std::string gait = quoted(kGait);
  requireOldOrNew("simulate --steps 1 --gait " + gait, "simulate --steps 30 --gait " + gait,
                  {"0.05", "0.2", "0.3", "0.35", "0.4", "0.45", "0.5", "0.6", "0.8", "1.2"});
  // diagnose: 4 files, about 1 s on 6 synthetic steps with a hidden knee friction.
  const std::string robot = quoted(kRobot);
  REQUIRE(box.run("synth --steps 6 --effect coulomb@knee_left=4 --robot " + robot + " --gait " +
                  gait + " --out data.csv")
              .exit_code == 0);
  const std::string diagnose = "diagnose --quiet --robot " + robot + " --data data.csv";
  requireOldOrNew(diagnose + " --effects viscous", diagnose,
                  {"0.1", "0.4", "0.7", "0.8", "0.9", "1.0", "1.1", "1.3", "2"});
  // stability: 4 files, about 3 s with the small studies below.
  const std::string stability = "stability --quiet --map-range 0.01 --margin-steps 1 "
                                "--ds-points 3 --gait " + gait;
  // (The sanitizer run, ten times slower, kills them before they publish: fewer delays.)
  const bool light = gaitopt::test::lightTests();
  requireOldOrNew(stability + " --map-points 3", stability + " --map-points 5",
                  light ? std::vector<std::string>{"1", "3"}
                        : std::vector<std::string>{"0.3", "1", "2", "2.5", "3", "3.5"});
  // evaluate: 2 files, about 0.5 s with a 5.5 MB trajectory.
  requireOldOrNew("evaluate --gait " + gait + " --sample-rate 100",
                  "evaluate --gait " + gait + " --sample-rate 10000",
                  {"0.05", "0.15", "0.3", "0.45", "0.6", "1"});
  // synth: one file, the truth its comment lines, about 0.5 s for 30 steps.
  const std::string synth = "synth --robot " + robot + " --gait " + gait;
  requireOldOrNew(synth + " --steps 3", synth + " --steps 30 --effect coulomb@knee_left=4",
                  {"0.05", "0.15", "0.3", "0.45", "0.6", "1"}, "walk.csv");
  // optimize: 3 files, 0.3 s to a few seconds of CPU at 0.6 m/s (the run's path depends on
  // the code); sweep: sweep.csv and one folder of 3 files per speed, about 2 s for two speeds.
  const std::string config = quoted(sourcePath("configs/default.yaml"));
  requireOldOrNew("optimize --quiet --config " + config,
                  "optimize --quiet --speed 0.6 --config " + config,
                  light ? std::vector<std::string>{"1", "5"}
                        : std::vector<std::string>{"0.05", "0.15", "0.3", "1", "2", "3"});
  const std::string sweep = "sweep --quiet --config " + config + " --speeds ";
  requireOldOrNew(sweep + "0.5:0.5:0.05", sweep + "0.5:0.55:0.05",
                  light ? std::vector<std::string>{"1", "5"}
                        : std::vector<std::string>{"0.5", "1.5", "3"});
  // impact-map: 2 files, about 3 s for 10^6 grid points.
  const std::string map = "impact-map --q=-0.367464,-3.018514,-3.135493,0.606892,-3.030679";
  requireOldOrNew(map + " --mu-range 0:1.5:10 --theta-range -180:0:10",
                  map + " --mu-range 0:1.5:1000 --theta-range -180:0:1000",
                  light ? std::vector<std::string>{"1", "3"}
                        : std::vector<std::string>{"0.2", "1", "2", "2.5", "3", "3.5"});
  // import-opensim --result: the CSV and the report, one folder published by one rename; about
  // 30 ms for the shipped trial with its analysis in Release (10 times more under the sanitizers).
  const std::string trial = "import-opensim --ik " + quoted(opensimIk()) + " --grf " +
                            quoted(opensimGrf()) + " --trc " + quoted(opensimTrc()) + " --id " +
                            quoted(opensimId()) + " --robot " +
                            quoted(sourcePath("configs/robot/human_subject01.yaml"));
  requireOldOrNew(trial + " --time-window 0:1.5", trial,
                  light ? std::vector<std::string>{"0.05", "1"}
                        : std::vector<std::string>{"0.005", "0.01", "0.015", "0.02", "0.025", "0.03",
                                                   "0.04", "0.1"},
                  "walk", "--result");
}
