#pragma once
// Command-line overrides of a configuration or gait file (`--set KEY=VALUE`, and the `--speed`
// and `--robot` shorthands): each replaces, or adds, the value at a dotted key of the YAML
// document before it is read, so an override is validated exactly like the file's own value.
// An error at an overridden key names the override instead of the file.
#include <functional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace gaitopt {

struct Override {
  std::string key;    // dotted path, e.g. "options.friction_coefficient"
  std::string value;  // a YAML scalar or flow collection, e.g. "0.7" or "{ss_points: 3}"
  std::string text() const { return key + "=" + value; }
};

// "KEY=VALUE": KEY of dot-separated names of letters, digits and '_', VALUE not empty.
// Throws ConfigError (file "--set") naming the text otherwise.
Override parseOverride(const std::string& text);

// `doc` (changed in place, its other nodes keep their lines) with every override applied in
// order, mappings created along a key's path. Throws ConfigError naming the override when a
// value is not valid YAML or a key's path crosses a value that is not a mapping.
YAML::Node withOverrides(YAML::Node doc, const std::vector<Override>& overrides);

// Runs `read`; a ConfigError of `file` at an overridden key (or inside it) is thrown again as
// "--set KEY=VALUE: key 'K': problem".
void attributeOverrideErrors(const std::string& file, const std::vector<Override>& overrides,
                             const std::function<void()>& read);

}  // namespace gaitopt
