#pragma once
// `--set KEY=VALUE` (repeatable) and the shorthands `--robot FILE` and `--speed V` of the
// commands that read a configuration or gait file: overrides of that file's keys
// (io/overrides.hpp), validated like the file and recorded in the outputs.
#include <optional>
#include <string>
#include <vector>

#include "gaitopt/io/overrides.hpp"

namespace CLI {
class App;
}

namespace gaitopt::cli {

struct OverrideArgs {
  std::string robot;
  std::optional<double> speed;
  std::vector<std::string> set;
};

// `speed_key`: the file's key that --speed sets ("speed" of a configuration,
// "options.target_speed" of a gait file); nullptr: no --speed.
void addOverrideOptions(CLI::App* cmd, OverrideArgs& args, const char* speed_key);

// --robot (made absolute: the file resolves relative paths against itself), then --speed, then
// every --set in order; a later override of the same key wins. Throws ConfigError for a
// malformed --set.
std::vector<Override> overridesOf(const OverrideArgs& args, const char* speed_key);

}  // namespace gaitopt::cli
