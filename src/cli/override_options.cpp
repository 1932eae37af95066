#include "override_options.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>

#include "cli_common.hpp"
#include "gaitopt/gait/options.hpp"

namespace gaitopt::cli {

void addOverrideOptions(CLI::App* cmd, OverrideArgs& args, const char* speed_key) {
  cmd->add_option("--robot", args.robot,
                  "Robot description file instead of the one the file names (--set robot=FILE, "
                  "relative to the current folder)")
      ->check(CLI::ExistingFile);
  if (speed_key)
    cmd->add_option("--speed", args.speed,
                    std::string("Walking speed [m/s] (--set ") + speed_key + "=V)")
        ->check(numberWithin(0.0, kMaxWalkingSpeed, true, "m/s"));
  cmd->add_option("--set", args.set,
                  "KEY=VALUE: the file's value at the dotted KEY replaced (or added), e.g. "
                  "--set options.friction_coefficient=0.7; repeatable, validated like the file");
}

std::vector<Override> overridesOf(const OverrideArgs& args, const char* speed_key) {
  std::vector<Override> out;
  if (!args.robot.empty())
    out.push_back({"robot", std::filesystem::absolute(args.robot).lexically_normal().string()});
  if (speed_key && args.speed) out.push_back({speed_key, shortNumber(*args.speed, "%.15g")});
  for (const std::string& s : args.set) out.push_back(parseOverride(s));
  return out;
}

}  // namespace gaitopt::cli
