#include "gaitopt/io/controller_export_file.hpp"

#include <array>
#include <stdexcept>

#include "gaitopt/io/file_digest.hpp"
#include "gaitopt/io/robot_file.hpp"

namespace gaitopt {
namespace {

constexpr const char* kFormat = "gaitopt controller export";
// Schema 1 files carried their version in the format string.
constexpr const char* kFormatV1 = "gaitopt controller export 1";

// Offset of the first top-level key of the JSON object `text` that starts the bulky part of an
// export (`phases`, `samples`), or npos. Strings are skipped with their escapes, so braces and
// key-like text inside the embedded YAML do not count.
std::size_t bulkStart(const std::string& text) {
  static const std::array<std::string, 2> bulk{"phases", "samples"};
  int depth = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '{' || c == '[') ++depth;
    if (c == '}' || c == ']') --depth;
    if (c != '"') continue;
    const std::size_t start = i;
    for (++i; i < text.size() && text[i] != '"'; ++i)
      if (text[i] == '\\') ++i;
    const std::size_t after = text.find_first_not_of(" \t\r\n", i + 1);
    const bool is_key = after != std::string::npos && text[after] == ':';
    const std::string name = text.substr(start + 1, i - start - 1);
    if (depth == 1 && is_key && (name == bulk[0] || name == bulk[1])) return start;
  }
  return std::string::npos;
}

// The export without its bulky part, still one JSON object.
std::string exportHead(const std::string& text) {
  const std::size_t cut = bulkStart(text);
  if (cut == std::string::npos) return text;
  std::string head = text.substr(0, cut);
  const std::size_t last = head.find_last_not_of(" \t\r\n,");
  return head.substr(0, last == std::string::npos ? 0 : last + 1) + "\n}\n";
}

// The file's text; an unreadable file is a ConfigError like every reader's.
std::string readText(const std::string& path) {
  try {
    return fileBytes(path);
  } catch (const std::runtime_error&) {
    throw ConfigError(path, "", 0, "cannot open the file for reading");
  }
}

// The embedded file `key` parsed; messages name "<path> [<key>.yaml]".
YAML::Node embeddedYaml(const YamlMap& entry, const std::string& key) {
  return parseYamlText(entry.string("yaml"), entry.file() + " [" + key + ".yaml]");
}

void requireFormat(const YamlMap& doc) {
  const std::string format = doc.has("format") ? doc.string("format") : "";
  if (format == kFormatV1)
    throw doc.error("format", "schema version 1 is not supported (this gaitopt reads schema " +
                                  std::to_string(kControllerExportSchema) +
                                  "): export the gait again");
  if (format != kFormat)
    throw doc.error("format", "not a gaitopt controller export (expected format \"" +
                                  std::string(kFormat) + "\")");
  const double version = doc.number("schema_version");
  if (version != kControllerExportSchema)
    throw doc.error("schema_version", "schema version " + doc.text("schema_version") +
                                          " is not supported (this gaitopt reads schema " +
                                          std::to_string(kControllerExportSchema) + ")");
}

}  // namespace

ControllerExport readControllerExport(const std::string& path) {
  const YAML::Node root = parseYamlText(exportHead(readText(path)), path);
  if (!root.IsMap())
    throw ConfigError(path, "", 0, "not a gaitopt controller export (expected a JSON object)");
  const YamlMap doc(root, path, "");
  requireFormat(doc);
  ControllerExport e;
  e.path = path;
  e.schema_version = kControllerExportSchema;

  const YamlMap gait = doc.map("gait");
  const YamlMap robot = doc.map("robot");
  const std::string gait_label = path + " [gait.yaml]";
  e.gait = parseGaitDocument(YamlMap(embeddedYaml(gait, "gait"), gait_label, ""));
  e.gait.path = path;
  e.gait.robot_path = robot.string("file");
  e.gait.robot = parseRobot(embeddedYaml(robot, "robot"), path + " [robot.yaml]");

  const YamlMap cyclic = doc.map("cyclic_gait");
  e.speed = cyclic.number("speed");
  e.step_length = cyclic.number("step_length");
  e.t_ss = cyclic.number("t_ss");
  e.t_ds = cyclic.number("t_ds");
  const YamlMap feedforward = doc.map("feedforward");
  e.rotor = choiceIndex(feedforward, "rotor_model", std::array<const char*, 2>{"exact",
                                                                              "high_gear"}) == 0
                ? RotorModel::Exact
                : RotorModel::HighGear;
  return e;
}

}  // namespace gaitopt
