#include "gaitopt/io/overrides.hpp"

#include <regex>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/yaml_reader.hpp"

namespace gaitopt {
namespace {

const char* const kSetOption = "--set";

std::vector<std::string> pathOf(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t dot; (dot = key.find('.', start)) != std::string::npos; start = dot + 1)
    parts.push_back(key.substr(start, dot - start));
  parts.push_back(key.substr(start));
  return parts;
}

bool covers(const Override& o, const std::string& key) {
  return key == o.key || key.rfind(o.key + ".", 0) == 0;
}

}  // namespace

Override parseOverride(const std::string& text) {
  static const std::regex form(R"(([A-Za-z0-9_]+(\.[A-Za-z0-9_]+)*)=(.+))");
  std::smatch m;
  if (!std::regex_match(text, m, form))
    throw ConfigError(kSetOption, "", 0,
                      "expected KEY=VALUE (KEY a dotted path such as options.ss_nodes, VALUE "
                      "not empty), got '" + printable(text) + "'");
  return {m[1].str(), m[3].str()};
}

YAML::Node withOverrides(YAML::Node doc, const std::vector<Override>& overrides) {
  if (!doc.IsMap()) return doc;  // the reader names that problem
  for (const Override& o : overrides) {
    const std::string where = std::string(kSetOption) + " " + o.text();
    YAML::Node value;
    try {
      value = parseYamlText(o.value, where);
    } catch (const ConfigError& e) {
      throw ConfigError(where, "", 0, e.problem());
    }
    const std::vector<std::string> path = pathOf(o.key);
    YAML::Node node = doc;  // the same node (YAML::Node copies share it), changed in place
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      if (!node[path[i]] || node[path[i]].IsNull()) node[path[i]] = YAML::Node(YAML::NodeType::Map);
      if (!node[path[i]].IsMap())
        throw ConfigError(where, o.key, 0, "'" + path[i] + "' does not hold a mapping");
      node.reset(node[path[i]]);
    }
    node[path.back()] = value;
  }
  return doc;
}

void attributeOverrideErrors(const std::string& file, const std::vector<Override>& overrides,
                             const std::function<void()>& read) {
  try {
    read();
  } catch (const ConfigError& e) {
    if (e.file() != file) throw;  // in another file the configuration names
    for (auto o = overrides.rbegin(); o != overrides.rend(); ++o)  // the last one wins
      if (covers(*o, e.key()))
        throw ConfigError(std::string(kSetOption) + " " + o->text(), e.key(), 0, e.problem());
    throw;
  }
}

}  // namespace gaitopt
