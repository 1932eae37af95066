#include "data_files.hpp"

#include <CLI/CLI.hpp>
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

void addRobotOption(CLI::App* cmd, std::string& target) {
  cmd->add_option("--robot", target,
                  std::string("Robot description YAML file (default: ") + kDefaultRobot +
                      " of gaitopt's data, " + dataDirectory().string() + ")")
      ->check(CLI::ExistingFile);
}

std::string robotOrDefault(const std::string& given, const char* command) {
  if (!given.empty()) return given;
  const std::string path = (dataDirectory() / kDefaultRobot).string();
  std::cerr << "gaitopt " << command << ": --robot not given: using " << path << "\n";
  return path;
}

}  // namespace gaitopt::cli
