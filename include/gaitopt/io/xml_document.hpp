#pragma once
// A strict reader for the XML subset that OpenSim writes (.osim models): elements, attributes,
// character data, comments and the <?xml ...?> declaration, with the entity references &lt;
// &gt; &amp; &quot; &apos; and numeric character references. Anything else (DOCTYPE, CDATA,
// other processing instructions, a mismatched end tag, text outside the root) is refused with
// the file and line, so a damaged model is named rather than half read.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace gaitopt {

struct XmlElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;  // in file order, unique names
  std::string text;  // the character data directly inside, entities decoded, pieces joined
  std::vector<XmlElement> children;
  int line = 0;  // 1-based line of the start tag

  // The attribute's value, or nullptr.
  const std::string* attribute(const std::string& attribute_name) const;
  // The first child element named `child_name`, or nullptr.
  const XmlElement* child(const std::string& child_name) const;
};

// Bounds that keep a hostile file from exhausting the process (docs/reliability.md): the
// deepest OpenSim model nests about 15 elements and the largest shipped by OpenSim is a few MB.
constexpr int kMaxXmlDepth = 64;
constexpr std::size_t kMaxXmlBytes = std::size_t{64} << 20;

// The root element of `text`; `file` names it in errors (ConfigError "<file>:<line>: problem").
XmlElement parseXml(const std::string& text, const std::string& file);

// parseXml of the file at `path`, read as an input file of at most kMaxXmlBytes bytes.
XmlElement readXmlFile(const std::string& path);

}  // namespace gaitopt
