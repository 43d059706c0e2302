#include "util/quoted_text.h"

#include <cstdio>
#include <vector>

namespace fenestra {

namespace {

// Length of the UTF-8 sequence starting at s[i] (1 to 4), or 0 when it is not well formed.
std::size_t utf8_length(const std::string& s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
  if (n == 0 || i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
  return n;
}

// Writes JSON text of `value` into `out`, stopping once `out` is longer than `limit`.
void append_json(const nlohmann::json& value, std::size_t limit, std::string* out) {
  using nlohmann::json;
  if (value.is_array() || value.is_object()) {
    const bool object = value.is_object();
    *out += object ? '{' : '[';
    bool first = true;
    for (auto it = value.begin(); it != value.end(); ++it) {
      if (out->size() > limit) return;
      if (!first) *out += ", ";
      first = false;
      if (object) *out += json(it.key().substr(0, limit)).dump(-1, ' ', false, json::error_handler_t::replace) + ": ";
      append_json(*it, limit, out);
    }
    *out += object ? '}' : ']';
  } else if (value.is_string()) {
    const std::string& s = value.get_ref<const std::string&>();
    *out += json(s.substr(0, limit + 1)).dump(-1, ' ', false, json::error_handler_t::replace);
  } else {
    *out += value.dump(-1, ' ', false, json::error_handler_t::replace);
  }
}

// Each character of `text`, printable: control characters as \uXXXX (a NUL as \u0000), bytes that
// are not UTF-8 as \xNN. Stops after `limit` characters.
std::vector<std::string> printable_characters(const std::string& text, std::size_t limit) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < text.size() && out.size() < limit) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const std::size_t n = utf8_length(text, i);
    char escaped[8];
    if (n == 0) {
      std::snprintf(escaped, sizeof escaped, "\\x%02X", c);
      out.emplace_back(escaped), i += 1;
    } else if (c < 0x20 || c == 0x7f) {
      std::snprintf(escaped, sizeof escaped, "\\u%04X", c);
      out.emplace_back(escaped), i += 1;
    } else {
      out.emplace_back(text, i, n), i += n;
    }
  }
  return out;
}

std::string joined(std::vector<std::string>::const_iterator begin, std::vector<std::string>::const_iterator end) {
  std::string out;
  for (auto it = begin; it != end; ++it) out += *it;
  return out;
}

}  // namespace

std::string quoted_text(const std::string& text) {
  const std::vector<std::string> chars = printable_characters(text, kMaxQuotedChars + 1);
  if (chars.size() <= kMaxQuotedChars) return joined(chars.begin(), chars.end());
  return joined(chars.begin(), chars.begin() + kMaxQuotedChars) + "...";
}

std::string quoted_path(const std::string& path) {
  const std::vector<std::string> chars = printable_characters(path, std::string::npos);
  if (chars.size() <= kMaxQuotedPathChars) return joined(chars.begin(), chars.end());
  return joined(chars.begin(), chars.begin() + kQuotedPathHead) + "..." +
         joined(chars.end() - kQuotedPathTail, chars.end());
}

std::string quoted_json(const nlohmann::json& value) {
  std::string out;
  append_json(value, 4 * kMaxQuotedChars, &out);
  return quoted_text(out);
}

}  // namespace fenestra
