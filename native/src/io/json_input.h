#pragma once
// Reading user JSON (scene and openings files) so that every error names the file, the line and
// column, and the key it happened under, in words rather than nlohmann's exception codes.
#include <nlohmann/json.hpp>

#include <string>

namespace fenestra {

// Parses `text`; on a syntax error or an out-of-range number throws std::invalid_argument
// "<what> '<name>' is not valid JSON: line L, column C (under key K): <reason>".
nlohmann::json parse_json_text(const std::string& text, const std::string& what, const std::string& name);

// nlohmann's message without its "[json.exception.type_error.302] " prefix.
std::string json_error_text(const std::exception& e);

}  // namespace fenestra
