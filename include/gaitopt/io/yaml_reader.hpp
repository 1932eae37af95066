#pragma once
// Strict, typed reading of one YAML mapping of a configuration file. Every problem (missing
// key, wrong type, non-finite number, wrong sequence length, key never read) becomes a
// ConfigError naming the file, the dotted key and its 1-based line. Shared by the robot,
// gait and optimiser loaders so that all config files fail the same, helpful way.
#include <yaml-cpp/yaml.h>

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gaitopt/io/config_error.hpp"

namespace gaitopt {

// Resource limits of every YAML reader (docs/reliability.md): beyond them the file is refused
// with a ConfigError instead of costing gigabytes or minutes.
struct YamlLimits {
  static constexpr std::size_t kMaxFileBytes = 1 << 20;  // 1 MiB
  static constexpr std::size_t kMaxLineBytes = 4096;
  static constexpr int kMaxNesting = 32;  // mappings/sequences inside each other
};

// Reads a YAML file. A missing, unreadable or unparsable file, one over the limits, one with
// control characters (binary data), more than one document (`---`) or none throws ConfigError
// with the file name and, where known, the line.
YAML::Node loadYamlFile(const std::string& path);
// The same checks on YAML `text` already in memory, `file` naming it in messages.
YAML::Node parseYamlText(const std::string& text, const std::string& file);

// View of a mapping node. Copies share the record of which keys were read, so a copy
// returned by map() and the parent's rejectUnknownKeys() see the same bookkeeping.
//
// Line numbers in errors: the key's line for anything about an existing key; for a
// missing key, the line of the mapping itself, i.e. of the key that introduces it
// ("masses:"), or for the document root the line of its first entry.
class YamlMap {
 public:
  // Throws ConfigError if `node` is not a mapping or has a duplicate key. `path_prefix` is
  // the dotted path of this mapping ("" for the document root).
  YamlMap(const YAML::Node& node, std::string file, std::string path_prefix);

  const std::string& file() const;
  std::string path(const std::string& key) const;  // dotted path of `key` in this mapping
  int line() const;                                // line of this mapping (see above)

  // Presence; names `key` among the valid keys of rejectUnknownKeys' message (a caller that
  // finds it present reads it or refuses it).
  bool has(const std::string& key) const;
  // Presence of `key` holding a mapping; does not count as reading the key.
  bool hasMapping(const std::string& key) const;

  // Required values. Numbers must be plain (unquoted) finite scalars; booleans exactly
  // `true` or `false` (not the YAML 1.1 spellings yes/no/on/off/y/n).
  double number(const std::string& key) const;
  std::string string(const std::string& key) const;
  bool boolean(const std::string& key) const;
  std::vector<double> numbers(const std::string& key, std::size_t expected_size) const;
  YamlMap map(const std::string& key) const;

  // Optional values: empty when the key is absent; a present key must be well formed.
  std::optional<double> optionalNumber(const std::string& key) const;
  std::optional<YamlMap> optionalMap(const std::string& key) const;

  // The scalar text of `key` (or of element `index` of sequence `key`) as the user wrote it,
  // printable; "" if absent or not a scalar. For messages that echo a value.
  std::string text(const std::string& key) const;
  std::string elementText(const std::string& key, std::size_t index) const;

  // Every entry of this mapping as (key, scalar text), in file order, for pass-through maps
  // whose keys are checked by someone else (e.g. Ipopt options); marks every key as read.
  // Quoted and plain scalars alike give their text; a sequence, mapping or null value is a
  // ConfigError at its key.
  std::vector<std::pair<std::string, std::string>> scalarEntries() const;

  // Throws for the first key of this mapping, or of any mapping obtained from it through
  // map()/optionalMap(), that was never asked for: catches misspelt keys, which would
  // otherwise silently fall back to defaults.
  void rejectUnknownKeys() const;

  // Errors for checks done by the caller (e.g. non-physical values), located at `key`
  // (its line if present, else this mapping's) or at element `index` of sequence `key`.
  ConfigError error(const std::string& key, const std::string& problem) const;
  ConfigError elementError(const std::string& key, std::size_t index,
                           const std::string& problem) const;

 private:
  struct State;
  YamlMap(const YAML::Node& node, std::string file, std::string path_prefix, int line);
  std::optional<std::pair<YAML::Node, YAML::Node>> find(const std::string& key) const;
  std::pair<YAML::Node, YAML::Node> require(const std::string& key) const;

  std::shared_ptr<State> state_;
};

// Helpers shared by the loaders.

// `value` as a stream writes it by default (six significant digits), for error messages.
std::string showNumber(double value);

// A documented physical range [min, max] of a number, each bound open or closed, with its
// unit; robot, gait and optimiser readers share these checks so every number is both finite
// and physically meaningful (docs/reliability.md).
struct Range {
  double min;
  double max;
  bool min_open = false;  // (min, ...] instead of [min, ...]
  const char* unit = "";
  bool contains(double v) const { return (min_open ? v > min : v >= min) && v <= max; }
  std::string describe() const;  // e.g. "(0, 1000] kg"
};

// The number at `key`, which must lie in `range`; otherwise a ConfigError at the key that
// quotes the value as written: "must be in (0, 1000] kg, got 1e300".
double numberIn(const YamlMap& m, const std::string& key, const Range& range);
// Absent: `fallback`; present: as numberIn.
double numberInOr(const YamlMap& m, const std::string& key, const Range& range, double fallback);
// A sequence of `size` numbers, each in `range` (errors at the element).
std::vector<double> numbersIn(const YamlMap& m, const std::string& key, std::size_t size,
                              const Range& range);

// The index of the string value of `key` among `count` `choices`; any other value is a
// ConfigError at `key` that lists the choices. The key must be present.
int choiceIndex(const YamlMap& m, const std::string& key, const char* const* choices,
                std::size_t count);
template <std::size_t N>
int choiceIndex(const YamlMap& m, const std::string& key,
                const std::array<const char*, N>& choices) {
  return choiceIndex(m, key, choices.data(), N);
}

// A file named in the configuration file `config_path`: an absolute path as is, a relative one
// against that file's directory; lexically normalised.
std::string resolveAgainstFile(const std::string& config_path, const std::string& file);

// The file named at `key` of `doc` (as `given`, resolved to `resolved`) must exist and be
// readable; otherwise a ConfigError at `key`, e.g. "robot file '/a/r.yaml' (from 'r.yaml',
// relative to the gait file's directory) does not exist or is not a regular file", with `what`
// = "robot file" and `document` = "gait file".
void requireReadableFile(const YamlMap& doc, const std::string& key, const std::string& what,
                         const std::string& resolved, const std::string& given,
                         const std::string& document);

}  // namespace gaitopt
