#pragma once
// The keys a JSON object may hold. Every section of the scene and openings files refuses the keys
// it does not read, naming the closest one it knows: a typo must not run with the defaults.
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace fenestra {

// The word of `known` closest to `word` (case-insensitive edit distance, a swap of neighbours
// counting one), or "" when none is close enough to be a likely typo of it.
std::string closest_word(const std::string& word, const std::vector<std::string>& known);

// " (did you mean `x`?)" for closest_word(word, known), or "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& known);

struct UnknownKey {
  std::string key;      // as given (for the key path; quote it with quoted_text)
  std::string message;  // "unknown key; did you mean `element_size`? (known: materials, groups, ...)"
};

// The first key of `object` that is not in `known`.
std::optional<UnknownKey> find_unknown_key(const nlohmann::json& object, const std::vector<std::string>& known);

}  // namespace fenestra
