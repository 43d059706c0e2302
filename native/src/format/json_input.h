#pragma once
// Reading user JSON (scene and openings files) so that every error names the file, the line and
// column, and the key it happened under, in words rather than nlohmann's.
#include <nlohmann/json.hpp>

#include <string>

namespace fenestra {

// Lists and objects nest at most this deep in a file Fenestra reads (its own nest a few levels).
constexpr std::size_t kMaxJsonDepth = 64;

// Parses `text`. Throws std::invalid_argument
//   "<what> '<name>' is not valid JSON: line L, column C (under key K): <reason>" on a syntax
//   error or a number out of range,
//   "<what> '<name>', line L: K: the key is given twice (first on line M) ..." for a duplicate key,
//   "<what> '<name>', line L, column C (under key K): lists and objects nest deeper than 64 ...".
nlohmann::json parse_json_text(const std::string& text, const std::string& what, const std::string& name);

// nlohmann's message in words, without its "[json.exception.type_error.302] " prefix.
std::string json_error_text(const std::exception& e);

}  // namespace fenestra
