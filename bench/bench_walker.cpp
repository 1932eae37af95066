// Reference walking controller benchmark: the controller through its C interface
// (gaitopt/control/walker.h, libgaitopt_walker) on the MuJoCo plant of examples/mujoco_walk
// (examples/mujoco_walk_sim.hpp), default gait (configs/gait/default_step.yaml) exported by
// `gaitopt export-model` and `gaitopt export --format json`, controller at 1 kHz:
// (1) one gaitopt_walker_torques call: the calls of a 20-step walk, target median ≤ 20 µs;
// (2) a 100-step walk, controller and MuJoCo (0.5 ms steps): wall time, target median ≤ 2 s
//     (each repeat is a whole walk: `--repeats 11` keeps the run short).
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "gaitopt/io/gait_file.hpp"
#include "mujoco_walk_sim.hpp"

using namespace gaitopt;
using namespace gaitopt::bench;

namespace {

constexpr const char* kGait = GAITOPT_SOURCE_DIR "/configs/gait/default_step.yaml";

// The gait's robot as MJCF and the gait as JSON in `dir`, written by the gaitopt program.
bool exportFiles(const std::filesystem::path& dir) {
  const std::string robot = loadGaitFile(kGait).robot.source_file;
  const std::string model = "'" GAITOPT_EXE "' export-model --format mjcf --robot '" + robot +
                            "' --out '" + (dir / "robot.xml").string() + "' > /dev/null";
  const std::string gait = "'" GAITOPT_EXE "' export --format json --gait '" +
                           std::string(kGait) + "' --out '" + (dir / "gait.json").string() +
                           "' > /dev/null";
  return std::system(model.c_str()) == 0 && std::system(gait.c_str()) == 0;
}

Stats callStats(std::vector<double> ns) {
  const SampleStats t = sampleStats(std::move(ns));
  Stats s;
  s.name = "walker_torques_call";
  s.description = "gaitopt_walker_torques, every call of a 20-step MuJoCo walk at 1 kHz, " +
                  std::string(kGait);
  s.median_ns = t.median;
  s.min_ns = t.min;
  s.p90_ns = t.p90;
  s.mean_ns = t.mean;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  BatchOptions opts;
  if (const auto status = parseBatchOptions(argc, argv, "bench_walker", 1, opts)) return *status;
  const Environment env;
  printEnvironment("bench_walker", env);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("bench_walker_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  std::vector<Stats> all;
  bool ok = exportFiles(dir);
  try {
    if (!ok) throw std::runtime_error("the export of " + std::string(kGait) + " failed");
    const mujoco_walk::WalkerPtr walker =
        mujoco_walk::loadWalker((dir / "gait.json").string(), "");
    const double speed = gaitopt_walker_speed(walker.get());
    mujoco_walk::WalkOptions walk;
    walk.model = (dir / "robot.xml").string();

    walk.steps = 20;
    std::vector<double> call_ns;
    const mujoco_walk::Summary short_walk = mujoco_walk::summarise(
        mujoco_walk::walkInMujoco(walk, walker.get(), &call_ns), walk.steps, speed);
    std::printf("gait:      %s, 20 steps %s (%+.2f %%), %zu controller calls\n", kGait,
                short_walk.walked ? "walked" : "NOT walked", short_walk.speed_error,
                call_ns.size());
    all.push_back(callStats(std::move(call_ns)));
    std::printf("%s: median %.2f us (min %.2f, p90 %.2f), target 20 us: %s\n",
                all.back().name.c_str(), all.back().median_ns * 1e-3, all.back().min_ns * 1e-3,
                all.back().p90_ns * 1e-3, verdict(all.back().median_ns * 1e-3, 20.0));

    walk.steps = 100;
    bool walked = true;
    all.push_back(measure(
        "walk_100_steps", std::string("100-step MuJoCo walk with the controller, ") + kGait,
        opts.batch, opts.repeats, [&]() {
          // A fresh controller per walk: it walks the gait from its initial state.
          const mujoco_walk::WalkerPtr w =
              mujoco_walk::loadWalker((dir / "gait.json").string(), "");
          const mujoco_walk::Outcome o = mujoco_walk::walkInMujoco(walk, w.get());
          walked = walked && mujoco_walk::summarise(o, walk.steps, speed).walked;
          return o.t_end;
        }));
    std::printf("%s: median %.3f s (min %.3f, p90 %.3f), target 2 s: %s%s\n",
                all.back().name.c_str(), all.back().median_ns * 1e-9, all.back().min_ns * 1e-9,
                all.back().p90_ns * 1e-9, verdict(all.back().median_ns * 1e-9, 2.0),
                walked ? "" : " (a walk FAILED)");
    ok = short_walk.walked && walked;
  } catch (const std::exception& e) {
    std::cerr << "bench_walker: error: " << e.what() << "\n";
    ok = false;
  }
  std::filesystem::remove_all(dir);
  if (!opts.json_path.empty()) {
    JsonWriter w;
    w.beginObject();
    writeEnvironment(w, "bench_walker", env);
    writeResultsArray(w, all);
    w.endObject();
    if (!writeJsonReport("bench_walker", opts.json_path, w)) return 1;
  }
  return ok ? 0 : 1;
}
