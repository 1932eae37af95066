#include "gaitopt/io/config_error.hpp"

#include <utility>

namespace gaitopt {

namespace {

// Length of the valid UTF-8 sequence starting at text[i], 0 if there is none.
std::size_t utf8Length(const std::string& text, std::size_t i) {
  const auto lead = static_cast<unsigned char>(text[i]);
  const std::size_t n = lead >= 0xf0 && lead <= 0xf4 ? 4 : lead >= 0xe0 ? 3 : lead >= 0xc2 ? 2 : 0;
  if (n == 0 || lead >= 0xf5 || i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(text[i + k]) & 0xc0) != 0x80) return 0;
  return n;
}

std::string hexEscape(unsigned char c) {
  const char* digits = "0123456789abcdef";
  return std::string("\\x") + digits[c >> 4] + digits[c & 15];
}

std::string formatMessage(const std::string& file, const std::string& key, int line,
                          const std::string& problem) {
  std::string message = printable(file);
  if (line > 0) message += ":" + std::to_string(line);
  message += ": ";
  if (!key.empty()) message += "key '" + printable(key) + "': ";
  return message + problem;
}

}  // namespace

std::string printable(const std::string& text, std::size_t max_bytes) {
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < max_bytes;) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x80) {
      const std::size_t n = utf8Length(text, i);
      out += n ? text.substr(i, n) : hexEscape(c);
      i += n ? n : 1;
      continue;
    }
    out += c < 0x20 || c == 0x7f ? hexEscape(c) : std::string(1, text[i]);
    ++i;
  }
  return text.size() > max_bytes ? out + "..." : out;
}

ConfigError::ConfigError(std::string file, std::string key, int line, const std::string& problem)
    : std::runtime_error(formatMessage(file, key, line, problem)),
      file_(std::move(file)),
      key_(std::move(key)),
      line_(line),
      problem_(problem) {}

}  // namespace gaitopt
