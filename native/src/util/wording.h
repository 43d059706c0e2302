#pragma once
// Counts in words a person reads: "1 opening", "2 openings".
#include <cstddef>
#include <string>

namespace fenestra {

// `n` and the noun, singular for exactly one (nouns that take an s).
inline std::string counted(size_t n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

}  // namespace fenestra
