#include "data_files.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <system_error>

namespace gaitopt::cli {
namespace fs = std::filesystem;

fs::path dataDirectory() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share" / "gaitopt";
    if (fs::is_directory(installed / "configs", ec)) return installed;
  }
  return fs::path(GAITOPT_SOURCE_DIR);
}

fs::path scriptsDir() {
  const char* env = std::getenv("GAITOPT_PLOT_SCRIPTS");
  return env && *env ? fs::path(env) : dataDirectory() / "scripts" / "plot";
}

std::vector<std::string> kinds(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const fs::path& p = entry.path();
    if (p.extension() == ".py" && p.stem().string().front() != '_') names.push_back(p.stem());
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> plotFigureNames() {
  std::vector<std::string> names = kinds(scriptsDir());
  for (std::string& kind : names) kind += ".png";
  return names;
}

void addRobotOption(CLI::App* cmd, std::string& target, const char* default_robot) {
  cmd->add_option("--robot", target,
                  std::string("Robot description YAML file (default: ") + default_robot +
                      " of gaitopt's data, " + dataDirectory().string() + ")")
      ->check(CLI::ExistingFile);
}

std::string robotOrDefault(const std::string& given, const char* command,
                           const char* default_robot) {
  if (!given.empty()) return given;
  const std::string path = (dataDirectory() / default_robot).string();
  std::cerr << "gaitopt " << command << ": --robot not given: using " << path << "\n";
  return path;
}

}  // namespace gaitopt::cli
