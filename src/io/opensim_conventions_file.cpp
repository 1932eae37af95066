#include "gaitopt/io/opensim_conventions_file.hpp"

#include <sstream>

#include "gaitopt/io/input_file.hpp"
#include "gaitopt/io/yaml_reader.hpp"

namespace gaitopt {

namespace {

constexpr std::size_t kMaxModelBytes = std::size_t{64} << 20;
const std::array<const char*, 2> kKneeSigns = {"negative", "positive"};

std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::optional<std::vector<std::string>> markerList(const YamlMap& m, const std::string& key) {
  if (!m.has(key)) return std::nullopt;
  const std::vector<std::string> names = words(m.string(key));
  if (names.empty()) throw m.error(key, "give at least one marker name");
  return names;
}

// The text of the first <tag>...</tag> after `from` in `xml`, and where it ends.
std::optional<std::string> element(const std::string& xml, const std::string& tag,
                                   std::size_t from, std::size_t before) {
  const std::size_t open = xml.find("<" + tag + ">", from);
  if (open == std::string::npos || open > before) return std::nullopt;
  const std::size_t start = open + tag.size() + 2;
  const std::size_t close = xml.find("</" + tag + ">", start);
  if (close == std::string::npos) return std::nullopt;
  return xml.substr(start, close - start);
}

}  // namespace

ConventionHints readConventionsFile(const std::string& path) {
  const YamlMap doc(loadYamlFile(path), path, "");
  ConventionHints h;
  if (const auto plates = doc.optionalMap("plates")) {
    h.right_plate = plates->string("right");
    h.left_plate = plates->string("left");
  }
  if (doc.has("knee_flexion")) {
    h.knee = choiceIndex(doc, "knee_flexion", kKneeSigns) == 1 ? KneeFlexion::Positive
                                                                : KneeFlexion::Negative;
    h.knee_source = "conventions file";
  }
  if (const auto c = doc.optionalMap("coordinates"))
    for (const auto& [name, column] : c->scalarEntries()) h.coordinates[name] = column;
  if (const auto m = doc.optionalMap("markers")) {
    h.pelvis_markers = markerList(*m, "pelvis");
    h.shoulder_markers = markerList(*m, "shoulders");
    h.heel_markers = markerList(*m, "heels");
    if (h.heel_markers && h.heel_markers->size() != 2)
      throw m->error("heels", "give two markers: right, left");
  }
  doc.rejectUnknownKeys();
  return h;
}

void addModelHints(const std::string& path, ConventionHints& hints) {
  const std::string xml = readInputFile(path, kMaxModelBytes, "64 MiB");
  const std::size_t model = xml.find("<Model name=\"");
  if (model == std::string::npos)
    throw ConfigError(path, "Model", 0, "no <Model name=...>: not an OpenSim model file");
  const std::size_t name_start = model + 13;
  hints.model = xml.substr(name_start, xml.find('"', name_start) - name_start);
  const std::size_t knee = xml.find("<Coordinate name=\"knee_angle_r\"");
  const std::size_t end = knee == std::string::npos ? knee : xml.find("</Coordinate>", knee);
  const std::optional<std::string> range =
      knee == std::string::npos ? std::nullopt : element(xml, "range", knee, end);
  std::istringstream in(range.value_or(""));
  double lo = 0.0, hi = 0.0;
  if (!(in >> lo >> hi))
    throw ConfigError(path, "knee_angle_r", 0, "no <range> of the knee_angle_r coordinate");
  if (hi <= 1.0 && lo >= -1.0)
    throw ConfigError(path, "knee_angle_r", 0,
                      "its range " + showNumber(lo) + " " + showNumber(hi) +
                          " rad does not tell the sign of knee flexion");
  const KneeFlexion sign = hi > 1.0 ? KneeFlexion::Positive : KneeFlexion::Negative;
  if (hints.knee && *hints.knee != sign)
    throw ConfigError(path, "knee_angle_r", 0,
                      "the model's knee_angle_r range " + showNumber(lo) + " " + showNumber(hi) +
                          " rad contradicts the knee_flexion of the conventions file");
  hints.knee = sign;
  hints.knee_source = "model " + hints.model + ", knee_angle_r range " + showNumber(lo) + ".." +
                      showNumber(hi) + " rad";
}

}  // namespace gaitopt
