#pragma once
// Where gaitopt finds its own data (the shipped robots, configurations and figure scripts): the
// installed share/gaitopt next to the executable's bin/ (relocatable: found from the
// executable's path), else the source tree the executable was built from. A default file is
// resolved there, not in the current folder, and the path used is printed.
#include <filesystem>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace gaitopt::cli {

constexpr const char* kDefaultRobot = "configs/robot/rabbit_miossec.yaml";

std::filesystem::path dataDirectory();

// The scripts of `gaitopt plot`: $GAITOPT_PLOT_SCRIPTS, else the data directory's scripts/plot.
std::filesystem::path scriptsDir();
// Figure kinds: the scripts KIND.py of `dir` (files starting with '_' are helpers), sorted.
std::vector<std::string> kinds(const std::filesystem::path& dir);
// The figures `gaitopt plot` writes into a run folder by default: KIND.png of each known kind.
std::vector<std::string> plotFigureNames();

// `--robot FILE`: empty `target` when not given (robotOrDefault then names the default,
// `default_robot` of the data directory).
void addRobotOption(CLI::App* cmd, std::string& target, const char* default_robot = kDefaultRobot);

// The robot file given, or `default_robot` of the data directory, printed on standard error
// as "gaitopt COMMAND: --robot not given: using PATH".
std::string robotOrDefault(const std::string& given, const char* command,
                           const char* default_robot = kDefaultRobot);

}  // namespace gaitopt::cli
