#include "gaitopt/io/yaml_reader.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>

#include "gaitopt/io/input_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

namespace gaitopt {

namespace {

using Entry = std::pair<YAML::Node, YAML::Node>;  // (key node, value node)

// yaml-cpp marks are 0-based with -1 for "no position"; messages use 1-based, 0 = unknown.
int lineOf(const YAML::Mark& mark) { return mark.line >= 0 ? mark.line + 1 : 0; }
int lineOf(const YAML::Node& node) { return lineOf(node.Mark()); }

// yaml-cpp tags quoted scalars "!" and plain ones "?": a quoted "5" is text, not a number.
bool isQuoted(const YAML::Node& node) { return node.Tag() == "!"; }

std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Sequence: return "a sequence";
    case YAML::NodeType::Map: return "a mapping";
    case YAML::NodeType::Scalar:
      return isQuoted(node) ? "the quoted string \"" + printable(node.Scalar()) + "\""
                            : "'" + printable(node.Scalar()) + "'";
    default: return "nothing (null)";
  }
}

std::optional<Entry> lookup(const YAML::Node& map, const std::string& key) {
  for (const auto& kv : map) {
    if (kv.first.Scalar() == key) return Entry{kv.first, kv.second};
  }
  return std::nullopt;
}

double toNumber(const YAML::Node& value, const std::string& file, const std::string& path,
                int line) {
  double number = 0.0;
  if (!value.IsScalar() || isQuoted(value) || !YAML::convert<double>::decode(value, number)) {
    throw ConfigError(file, path, line, "expected a number, got " + describe(value));
  }
  if (!std::isfinite(number)) {
    throw ConfigError(file, path, line, "expected a finite number, got " + describe(value));
  }
  return number;
}

std::string elementPath(const std::string& sequence_path, std::size_t index) {
  return sequence_path + "[" + std::to_string(index) + "]";
}

// Deepest chain of mappings/sequences inside `node` (a scalar is 0). Every node visited is taken
// from `budget`; at 0 the walk stops and returns `limit`. An alias stands for its anchor's
// whole subtree, so a few hundred bytes of nested aliases can stand for 10^9 nodes (an "alias
// bomb"): the budget bounds the walk, and every later reading of the document, to the nodes a
// file of its size can hold without aliases.
int nesting(const YAML::Node& node, int limit, std::size_t& budget) {
  if (budget == 0) return limit;
  --budget;
  if (!node.IsMap() && !node.IsSequence()) return 0;
  int deepest = 0;
  for (const auto& item : node) {
    if (node.IsMap()) deepest = std::max(deepest, nesting(item.first, limit, budget));
    const YAML::Node child = node.IsMap() ? item.second : YAML::Node(item);
    deepest = std::max(deepest, nesting(child, limit, budget));
    if (deepest >= limit) break;  // enough to refuse; alias loops stay bounded too
  }
  return deepest + 1;
}

// Records where documents start; ignores everything else.
class DocumentStarts : public YAML::EventHandler {
 public:
  std::vector<YAML::Mark> starts;
  void OnDocumentStart(const YAML::Mark& mark) override { starts.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

// The line of a second document in `text` (already parsed once), 0 if there is none. Parsed
// one document at a time, at most two: yaml-cpp 0.7's LoadAll loops forever on some invalid
// input (e.g. a line starting with ','; jbeder/yaml-cpp#1040, fixed upstream in #1319), where
// the parser reports ever more empty documents. A real second document needs a '---' or '...'
// marker line, which those bogus ones lack; so without one the text is not parsed a second
// time (that parse doubled the cost of every load).
int secondDocumentLine(const std::string& text) {
  const bool marker = text.rfind("---", 0) == 0 || text.rfind("...", 0) == 0 ||
                      text.find("\n---") != std::string::npos ||
                      text.find("\n...") != std::string::npos;
  if (!marker) return 0;
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentStarts handler;
  if (!parser.HandleNextDocument(handler) || !parser.HandleNextDocument(handler)) return 0;
  return handler.starts.size() > 1 ? std::max(1, lineOf(handler.starts[1])) : 0;
}

ConfigError tooLarge(const std::string& file) {
  return ConfigError(file, "", 0, "file larger than " +
                                      std::to_string(YamlLimits::kMaxFileBytes) + " bytes (limit)");
}

// Text checks done before parsing: size, line length and control characters (binary data
// would otherwise be echoed to the terminal by the parser's messages).
void checkText(const std::string& text, const std::string& file) {
  if (text.size() > YamlLimits::kMaxFileBytes) {
    throw tooLarge(file);
  }
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    const bool end = i == text.size() || text[i] == '\n';
    if (end && i - line_start > YamlLimits::kMaxLineBytes) {
      throw ConfigError(file, "", line, "line longer than " +
                                            std::to_string(YamlLimits::kMaxLineBytes) +
                                            " bytes (limit)");
    }
    if (end) {
      ++line;
      line_start = i + 1;
      continue;
    }
    const auto c = static_cast<unsigned char>(text[i]);
    if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f) {
      throw ConfigError(file, "", line, "control character " + printable(std::string(1, text[i])) +
                                            ": not a text file");
    }
  }
}

std::string joined(const std::set<std::string>& names) {
  std::string list;
  for (const auto& name : names) list += (list.empty() ? "" : ", ") + name;
  return list;
}

}  // namespace

struct YamlMap::State {
  YAML::Node node;
  std::string file;
  std::string prefix;
  int line = 0;
  std::set<std::string> known;    // every key asked for, present or not
  std::vector<YamlMap> children;  // mappings opened from this one, for rejectUnknownKeys()
};

YAML::Node loadYamlFile(const std::string& path) {
  return parseYamlText(
      readInputFile(path, YamlLimits::kMaxFileBytes,
                    std::to_string(YamlLimits::kMaxFileBytes) + " bytes"),
      path);
}

YAML::Node parseYamlText(const std::string& text, const std::string& file) {
  checkText(text, file);
  YAML::Node document;
  int second_document = 0;
  try {
    document = YAML::Load(text);
    second_document = secondDocumentLine(text);  // may find a syntax error after the first
  } catch (const YAML::DeepRecursion& e) {
    throw ConfigError(file, "", lineOf(e.mark), "nested deeper than " +
                                                    std::to_string(YamlLimits::kMaxNesting) +
                                                    " levels (limit)");
  } catch (const YAML::Exception& e) {
    throw ConfigError(file, "", lineOf(e.mark), "invalid YAML: " + e.msg);
  }
  if (second_document > 0) {
    throw ConfigError(file, "", second_document,
                      "a second YAML document ('---'): one document per file");
  }
  // Without aliases a node takes at least one byte (a null one an indicator beside it).
  std::size_t budget = 2 * text.size() + 16;
  const int depth = nesting(document, YamlLimits::kMaxNesting + 1, budget);
  if (budget == 0) {
    throw ConfigError(file, "", 0, "more than " + std::to_string(2 * text.size() + 16) +
                                       " nodes once aliases are expanded (limit: twice the "
                                       "file's bytes); write the values out instead of '*' "
                                       "aliases");
  }
  if (depth > YamlLimits::kMaxNesting) {
    throw ConfigError(file, "", 0, "nested deeper than " +
                                       std::to_string(YamlLimits::kMaxNesting) + " levels (limit)");
  }
  return document;
}

YamlMap::YamlMap(const YAML::Node& node, std::string file, std::string path_prefix)
    : YamlMap(node, std::move(file), std::move(path_prefix), lineOf(node)) {}

YamlMap::YamlMap(const YAML::Node& node, std::string file, std::string path_prefix, int line)
    : state_(std::make_shared<State>()) {
  state_->node = node;
  state_->file = std::move(file);
  state_->prefix = std::move(path_prefix);
  state_->line = line;
  if (!node.IsMap()) {
    throw ConfigError(state_->file, state_->prefix, line,
                      "expected a mapping, got " + describe(node));
  }
  std::set<std::string> seen;
  for (const auto& kv : node) {
    // A repeated key is almost always an editing slip; yaml-cpp would keep the first silently.
    if (!kv.first.IsScalar() || !seen.insert(kv.first.Scalar()).second) {
      throw ConfigError(state_->file, path(kv.first.Scalar()), lineOf(kv.first),
                        kv.first.IsScalar() ? "duplicate key" : "keys must be plain names");
    }
  }
}

const std::string& YamlMap::file() const { return state_->file; }

std::string YamlMap::path(const std::string& key) const {
  return state_->prefix.empty() ? key : state_->prefix + "." + key;
}

int YamlMap::line() const { return state_->line; }

bool YamlMap::has(const std::string& key) const {
  state_->known.insert(key);  // a key the reader asks about is one of the file's valid keys
  return lookup(state_->node, key).has_value();
}

bool YamlMap::hasMapping(const std::string& key) const {
  const auto entry = lookup(state_->node, key);
  return entry && entry->second.IsMap();
}

std::optional<Entry> YamlMap::find(const std::string& key) const {
  state_->known.insert(key);
  return lookup(state_->node, key);
}

Entry YamlMap::require(const std::string& key) const {
  auto entry = find(key);
  if (!entry) throw ConfigError(file(), path(key), line(), "required key is missing");
  return *entry;
}

double YamlMap::number(const std::string& key) const {
  const auto [k, v] = require(key);
  return toNumber(v, file(), path(key), lineOf(k));
}

std::optional<double> YamlMap::optionalNumber(const std::string& key) const {
  if (!has(key)) {
    state_->known.insert(key);
    return std::nullopt;
  }
  return number(key);
}

std::string YamlMap::string(const std::string& key) const {
  const YAML::Node v = require(key).second;
  if (!v.IsScalar()) throw error(key, "expected a string, got " + describe(v));
  return v.Scalar();
}

bool YamlMap::boolean(const std::string& key) const {
  const YAML::Node v = require(key).second;
  // Only the spellings the docs list: YAML 1.1's yes/no/on/off are easy to write by mistake.
  if (!v.IsScalar() || isQuoted(v) || (v.Scalar() != "true" && v.Scalar() != "false")) {
    throw error(key, "expected true or false, got " + describe(v));
  }
  return v.Scalar() == "true";
}

std::vector<double> YamlMap::numbers(const std::string& key, std::size_t expected_size) const {
  const YAML::Node v = require(key).second;
  const std::string expected =
      "expected a sequence of " + std::to_string(expected_size) + " numbers";
  if (!v.IsSequence()) throw error(key, expected + ", got " + describe(v));
  if (v.size() != expected_size) {
    throw error(key, expected + ", got " + std::to_string(v.size()));
  }
  std::vector<double> values;
  for (std::size_t i = 0; i < expected_size; ++i) {
    values.push_back(toNumber(v[i], file(), elementPath(path(key), i), lineOf(v[i])));
  }
  return values;
}

YamlMap YamlMap::map(const std::string& key) const {
  const auto [k, v] = require(key);
  YamlMap child(v, file(), path(key), lineOf(k));
  state_->children.push_back(child);
  return child;
}

std::optional<YamlMap> YamlMap::optionalMap(const std::string& key) const {
  if (!has(key)) {
    state_->known.insert(key);
    return std::nullopt;
  }
  return map(key);
}

std::string YamlMap::text(const std::string& key) const {
  const auto entry = lookup(state_->node, key);
  return entry && entry->second.IsScalar() ? printable(entry->second.Scalar()) : "";
}

std::string YamlMap::elementText(const std::string& key, std::size_t index) const {
  const auto entry = lookup(state_->node, key);
  if (!entry || !entry->second.IsSequence() || index >= entry->second.size()) return "";
  const YAML::Node element = entry->second[index];
  return element.IsScalar() ? printable(element.Scalar()) : "";
}

std::vector<std::pair<std::string, std::string>> YamlMap::scalarEntries() const {
  std::vector<std::pair<std::string, std::string>> entries;
  for (const auto& kv : state_->node) {
    const std::string key = kv.first.Scalar();
    state_->known.insert(key);
    if (!kv.second.IsScalar()) {
      throw error(key, "expected a single value, got " + describe(kv.second));
    }
    entries.emplace_back(key, kv.second.Scalar());
  }
  return entries;
}

void YamlMap::rejectUnknownKeys() const {
  for (const auto& kv : state_->node) {
    if (state_->known.count(kv.first.Scalar()) == 0) {
      throw ConfigError(file(), path(kv.first.Scalar()), lineOf(kv.first),
                        "unknown key (expected one of: " + joined(state_->known) + ")");
    }
  }
  for (const auto& child : state_->children) child.rejectUnknownKeys();
}

ConfigError YamlMap::error(const std::string& key, const std::string& problem) const {
  const auto entry = lookup(state_->node, key);
  return ConfigError(file(), path(key), entry ? lineOf(entry->first) : line(), problem);
}

ConfigError YamlMap::elementError(const std::string& key, std::size_t index,
                                  const std::string& problem) const {
  const auto entry = lookup(state_->node, key);
  int at = entry ? lineOf(entry->first) : line();
  if (entry && entry->second.IsSequence() && index < entry->second.size()) {
    at = lineOf(entry->second[index]);
  }
  return ConfigError(file(), elementPath(path(key), index), at, problem);
}

std::string showNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string Range::describe() const {
  return std::string(min_open ? "(" : "[") + showNumber(min) + ", " + showNumber(max) + "]" +
         (*unit ? std::string(" ") + unit : std::string());
}

double numberIn(const YamlMap& m, const std::string& key, const Range& range) {
  const double value = m.number(key);
  if (!range.contains(value)) {
    throw m.error(key, "must be in " + range.describe() + ", got " + m.text(key));
  }
  return value;
}

double numberInOr(const YamlMap& m, const std::string& key, const Range& range, double fallback) {
  return m.optionalNumber(key) ? numberIn(m, key, range) : fallback;
}

std::vector<double> numbersIn(const YamlMap& m, const std::string& key, std::size_t size,
                              const Range& range) {
  const std::vector<double> values = m.numbers(key, size);
  for (std::size_t i = 0; i < size; ++i) {
    if (!range.contains(values[i])) {
      throw m.elementError(key, i, "must be in " + range.describe() + ", got " +
                                       m.elementText(key, i));
    }
  }
  return values;
}

int choiceIndex(const YamlMap& m, const std::string& key, const char* const* choices,
                std::size_t count) {
  const std::string v = m.string(key);
  std::string list;
  for (std::size_t i = 0; i < count; ++i) {
    if (v == choices[i]) return static_cast<int>(i);
    list += (i == 0 ? "'" : ", '") + std::string(choices[i]) + "'";
  }
  throw m.error(key, "expected one of " + list + ", got '" + printable(v) + "'");
}

std::string resolveAgainstFile(const std::string& config_path, const std::string& file) {
  const std::filesystem::path f(file);
  if (f.is_absolute()) return f.lexically_normal().string();
  return (std::filesystem::path(config_path).parent_path() / f).lexically_normal().string();
}

void requireReadableFile(const YamlMap& doc, const std::string& key, const std::string& what,
                         const std::string& resolved, const std::string& given,
                         const std::string& document) {
  std::error_code ec;
  const std::string where = what + " '" + resolved + "' (from '" + given + "', relative to the " +
                            document + "'s directory)";
  if (!std::filesystem::is_regular_file(resolved, ec)) {
    throw doc.error(key, where + " does not exist or is not a regular file");
  }
  if (!std::ifstream(resolved)) throw doc.error(key, where + " cannot be read");
}

}  // namespace gaitopt
