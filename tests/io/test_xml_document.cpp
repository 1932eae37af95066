// The XML subset reader of the .osim models: what OpenSim writes is read, everything else is
// refused with the file and line.
#include <catch2/catch.hpp>

#include <string>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/xml_document.hpp"

using gaitopt::ConfigError;
using gaitopt::parseXml;
using gaitopt::XmlElement;
using Catch::Matchers::Contains;

namespace {

// parseXml(text) must fail at `line` with a message containing `problem`.
void requireXmlError(const std::string& text, int line, const std::string& problem) {
  try {
    parseXml(text, "m.osim");
    FAIL("no ConfigError for: " << text);
  } catch (const ConfigError& e) {
    INFO(e.what());
    CHECK(e.file() == "m.osim");
    CHECK(e.line() == line);
    CHECK_THAT(std::string(e.what()), Contains("m.osim:" + std::to_string(line) + ": "));
    CHECK_THAT(std::string(e.what()), Contains(problem));
  }
}

}  // namespace

TEST_CASE("xml: elements, attributes, text, comments and entities", "[xml]") {
  const XmlElement root = parseXml(
      "\xEF\xBB\xBF<?xml version=\"1.0\" encoding=\"UTF-8\" ?>\n"
      "<!-- a model -->\n"
      "<Doc Version='40000' note=\"a &lt;b&gt; &amp; &quot;c&quot; &apos;d&apos;\">\n"
      "  <mass>1.5</mass><!-- kg -->\n"
      "  <empty />\n"
      "  <name>x&#65;&#x42;&#xe9;y</name>\n"
      "  <mass>2</mass>\n"
      "</Doc>\n<!-- end -->\n",
      "m.osim");
  CHECK(root.name == "Doc");
  CHECK(root.line == 3);
  REQUIRE(root.attribute("Version"));
  CHECK(*root.attribute("Version") == "40000");
  CHECK(*root.attribute("note") == "a <b> & \"c\" 'd'");
  CHECK(root.attribute("missing") == nullptr);
  REQUIRE(root.children.size() == 4);
  CHECK(root.child("mass")->text == "1.5");  // the first of two
  CHECK(root.child("mass")->line == 4);
  CHECK(root.child("empty")->children.empty());
  CHECK(root.child("empty")->text.empty());
  CHECK(root.child("name")->text == "xAB\xC3\xA9y");
  CHECK(root.children[3].text == "2");
  CHECK(root.child("nothing") == nullptr);
}

TEST_CASE("xml: malformed documents are refused with their line", "[xml]") {
  requireXmlError("<a>\n<b>\n</a>", 3, "end tag 'a' does not match 'b' opened on line 2");
  requireXmlError("<a>\n<b>", 2, "element 'b' opened on line 2 is not closed");
  requireXmlError("<a>&nbsp;</a>", 1, "unknown entity '&nbsp;'");
  requireXmlError("<a>&#0;</a>", 1, "bad character reference");
  requireXmlError("<a>&#x110000;</a>", 1, "bad character reference");
  requireXmlError("<a>&amp</a>", 1, "unterminated '&' reference");
  requireXmlError("<!DOCTYPE a>\n<a/>", 1, "DOCTYPE declarations are not read");
  requireXmlError("<a>\n<![CDATA[x]]></a>", 2, "CDATA sections are not read");
  requireXmlError("<a/>\n<?pi x?>", 2, "processing instructions");
  requireXmlError("<a x='1' x='2'/>", 1, "duplicate attribute 'x'");
  requireXmlError("<a x='1'y='2'/>", 1, "expected whitespace between the attributes");
  requireXmlError("<a x=1/>", 1, "expected a quoted attribute value");
  requireXmlError("<a x='<'/>", 1, "'<' inside an attribute value");
  requireXmlError("<a/>\n<b/>", 2, "content after the root element 'a'");
  requireXmlError("<a/>\ntext", 2, "content after the root element");
  requireXmlError("\n\n", 3, "expected the root element");
  requireXmlError("<a>\n<!-- x -- y --></a>", 2, "'--' inside a comment");
  requireXmlError("<a><!-- x </a>", 1, "unterminated comment");
  requireXmlError("<a>]]></a>", 1, "']]>' in character data");
  requireXmlError(std::string("<a>\n\x01</a>"), 2, "control character \\x01");
  requireXmlError("<?xml version='1.0' encoding='ISO-8859-1'?><a/>", 1, "only UTF-8");
  requireXmlError("<1a/>", 1, "expected an element name");
}

TEST_CASE("xml: nesting deeper than the limit is refused", "[xml][reliability]") {
  std::string ok, deep;
  for (int i = 0; i < gaitopt::kMaxXmlDepth; ++i) ok += "<a>";
  for (int i = 0; i < gaitopt::kMaxXmlDepth; ++i) ok += "</a>";
  CHECK_NOTHROW(parseXml(ok, "m.osim"));
  for (int i = 0; i <= gaitopt::kMaxXmlDepth; ++i) deep += "<a>\n";
  requireXmlError(deep, gaitopt::kMaxXmlDepth + 1, "nested deeper than 64 (limit)");
}
