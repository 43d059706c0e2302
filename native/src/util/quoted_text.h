#pragma once
// User text echoed in a message (a value, a key, a token, a path): cut to about 80 characters
// with "..." so that no message grows with the input, and made printable.
#include <nlohmann/json.hpp>

#include <string>

namespace fenestra {

constexpr std::size_t kMaxQuotedChars = 80;

// `text` with control characters written \uXXXX (a NUL as \u0000), bytes that are not UTF-8 as
// \xNN, and cut after kMaxQuotedChars characters with "..." appended.
std::string quoted_text(const std::string& text);

// A file path made printable the same way; a path longer than kMaxQuotedPathChars keeps its first
// kQuotedPathHead and last kQuotedPathTail characters (where it starts, and the file it names)
// around "...".
constexpr std::size_t kMaxQuotedPathChars = 200, kQuotedPathHead = 60, kQuotedPathTail = 120;
std::string quoted_path(const std::string& path);

// A JSON value as JSON text, cut the same way; a large list or object is not written out whole
// first.
std::string quoted_json(const nlohmann::json& value);

}  // namespace fenestra
