#include "gaitopt/io/xml_document.hpp"

#include <cstdint>

#include "gaitopt/io/config_error.hpp"
#include "gaitopt/io/input_file.hpp"

namespace gaitopt {

const std::string* XmlElement::attribute(const std::string& attribute_name) const {
  for (const auto& [key, value] : attributes)
    if (key == attribute_name) return &value;
  return nullptr;
}

const XmlElement* XmlElement::child(const std::string& child_name) const {
  for (const XmlElement& c : children)
    if (c.name == child_name) return &c;
  return nullptr;
}

namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool isNameStart(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_' || c == ':' ||
         static_cast<unsigned char>(c) >= 0x80;
}
bool isNameChar(char c) {
  return isNameStart(c) || (c >= '0' && c <= '9') || c == '-' || c == '.';
}

// UTF-8 bytes of code point `cp` (a valid XML character, checked by the caller).
std::string utf8(std::uint32_t cp) {
  std::string out;
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
  return out;
}

bool isXmlChar(std::uint32_t cp) {
  return cp == 0x9 || cp == 0xA || cp == 0xD || (cp >= 0x20 && cp <= 0xD7FF) ||
         (cp >= 0xE000 && cp <= 0xFFFD) || (cp >= 0x10000 && cp <= 0x10FFFF);
}

class XmlParser {
 public:
  XmlParser(const std::string& text, const std::string& file) : text_(text), file_(file) {}

  XmlElement document() {
    if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;  // UTF-8 byte-order mark
    if (startsWith("<?xml")) declaration();
    miscellany();
    if (atEnd() || peek() != '<') fail("expected the root element");
    XmlElement root = element(1);
    miscellany();
    if (!atEnd()) fail("content after the root element '" + root.name + "'");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw ConfigError(file_, "", line_, problem);
  }
  bool atEnd() const { return pos_ >= text_.size(); }
  char peek() const { return text_[pos_]; }
  bool startsWith(const char* s) const { return text_.compare(pos_, std::char_traits<char>::length(s), s) == 0; }
  void advance(std::size_t n = 1) {
    for (std::size_t i = 0; i < n && !atEnd(); ++i, ++pos_)
      if (text_[pos_] == '\n') ++line_;
  }
  void refuseControl(char c) const {
    if ((static_cast<unsigned char>(c) < 0x20 && !isSpace(c)) || c == 0x7F)
      fail("control character " + printable(std::string(1, c)) + " in the text");
  }
  void skipSpace() {
    while (!atEnd() && isSpace(peek())) advance();
  }
  void expect(char c, const std::string& where) {
    if (atEnd() || peek() != c) fail(std::string("expected '") + c + "' " + where);
    advance();
  }

  // Text up to `terminator` (consumed), which must come before the end of the file.
  std::string until(const char* terminator, const std::string& what) {
    const std::size_t end = text_.find(terminator, pos_);
    if (end == std::string::npos) fail("unterminated " + what);
    std::string body = text_.substr(pos_, end - pos_);
    advance(end - pos_ + std::char_traits<char>::length(terminator));
    return body;
  }

  void declaration() {
    advance(5);
    const std::string body = until("?>", "XML declaration");
    if (body.find("encoding") != std::string::npos && body.find("UTF-8") == std::string::npos &&
        body.find("utf-8") == std::string::npos)
      fail("only UTF-8 encoded XML is read");
  }

  void comment() {
    advance(4);
    const std::string body = until("-->", "comment");
    if (body.find("--") != std::string::npos) fail("'--' inside a comment");
  }

  // Whitespace and comments between top-level constructs.
  void miscellany() {
    for (;;) {
      skipSpace();
      if (startsWith("<!--")) {
        comment();
      } else if (startsWith("<!DOCTYPE")) {
        fail("DOCTYPE declarations are not read");
      } else if (startsWith("<?")) {
        fail("processing instructions other than the XML declaration are not read");
      } else {
        return;
      }
    }
  }

  std::string name(const std::string& what) {
    if (atEnd() || !isNameStart(peek())) fail("expected " + what);
    const std::size_t start = pos_;
    while (!atEnd() && isNameChar(peek())) advance();
    return text_.substr(start, pos_ - start);
  }

  // An entity or character reference after its '&'.
  std::string reference() {
    const std::size_t end = text_.find(';', pos_);
    if (end == std::string::npos || end - pos_ > 12) fail("unterminated '&' reference");
    const std::string ref = text_.substr(pos_, end - pos_);
    advance(end - pos_ + 1);
    if (ref == "lt") return "<";
    if (ref == "gt") return ">";
    if (ref == "amp") return "&";
    if (ref == "quot") return "\"";
    if (ref == "apos") return "'";
    if (ref.size() >= 2 && ref[0] == '#') {
      const bool hex = ref[1] == 'x';
      const std::string digits = ref.substr(hex ? 2 : 1);
      std::uint32_t cp = 0;
      for (const char c : digits) {
        int d;
        if (c >= '0' && c <= '9') d = c - '0';
        else if (hex && c >= 'a' && c <= 'f') d = c - 'a' + 10;
        else if (hex && c >= 'A' && c <= 'F') d = c - 'A' + 10;
        else fail("bad character reference '&" + ref + ";'");
        cp = cp * (hex ? 16 : 10) + static_cast<std::uint32_t>(d);
        if (cp > 0x10FFFF) break;
      }
      if (digits.empty() || !isXmlChar(cp)) fail("bad character reference '&" + ref + ";'");
      return utf8(cp);
    }
    fail("unknown entity '&" + ref + ";' (only &lt; &gt; &amp; &quot; &apos; are defined)");
  }

  std::string attributeValue() {
    if (atEnd() || (peek() != '"' && peek() != '\'')) fail("expected a quoted attribute value");
    const char quote = peek();
    advance();
    std::string value;
    for (;;) {
      if (atEnd()) fail("unterminated attribute value");
      const char c = peek();
      if (c == quote) break;
      if (c == '<') fail("'<' inside an attribute value");
      refuseControl(c);
      advance();
      value += c == '&' ? reference() : std::string(1, c);
    }
    advance();
    return value;
  }

  // The start tag's attributes; true when the tag closes itself ("/>").
  bool attributes(XmlElement& e) {
    for (;;) {
      const bool spaced = !atEnd() && isSpace(peek());
      skipSpace();
      if (atEnd()) fail("unterminated start tag of '" + e.name + "'");
      if (startsWith("/>")) {
        advance(2);
        return true;
      }
      if (peek() == '>') {
        advance();
        return false;
      }
      if (!spaced) fail("expected whitespace between the attributes of '" + e.name + "'");
      std::string key = name("an attribute name in '" + e.name + "'");
      if (e.attribute(key)) fail("duplicate attribute '" + key + "' in '" + e.name + "'");
      skipSpace();
      expect('=', "after attribute '" + key + "'");
      skipSpace();
      e.attributes.emplace_back(std::move(key), attributeValue());
    }
  }

  XmlElement element(int depth) {
    if (depth > kMaxXmlDepth)
      fail("elements nested deeper than " + std::to_string(kMaxXmlDepth) + " (limit)");
    XmlElement e;
    e.line = line_;
    advance();  // '<'
    e.name = name("an element name");
    if (attributes(e)) return e;
    for (;;) {
      if (atEnd()) fail("element '" + e.name + "' opened on line " + std::to_string(e.line) + " is not closed");
      const char c = peek();
      if (c == '<') {
        if (startsWith("</")) break;
        if (startsWith("<!--")) comment();
        else if (startsWith("<![CDATA[")) fail("CDATA sections are not read");
        else if (startsWith("<!") || startsWith("<?")) fail("unexpected markup in '" + e.name + "'");
        else e.children.push_back(element(depth + 1));
      } else {
        refuseControl(c);
        advance();
        if (c == '&') e.text += reference();
        else if (c == '>' && pos_ >= 3 && text_.compare(pos_ - 3, 3, "]]>") == 0) fail("']]>' in character data");
        else e.text += c;
      }
    }
    advance(2);
    const std::string closing = name("an end-tag name");
    if (closing != e.name)
      fail("end tag '" + closing + "' does not match '" + e.name + "' opened on line " + std::to_string(e.line));
    skipSpace();
    expect('>', "to close the end tag of '" + e.name + "'");
    return e;
  }

  const std::string& text_;
  const std::string& file_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

}  // namespace

XmlElement parseXml(const std::string& text, const std::string& file) {
  return XmlParser(text, file).document();
}

XmlElement readXmlFile(const std::string& path) {
  return parseXml(readInputFile(path, kMaxXmlBytes, "64 MiB"), path);
}

}  // namespace gaitopt
