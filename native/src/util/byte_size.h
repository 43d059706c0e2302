#pragma once
// Sizes in bytes as people write and read them: "8G", "512M", "1.5GB", "2GiB" in, "11.5 GB" out.
// Decimal units (k = 1e3, M = 1e6, G = 1e9, T = 1e12), binary ones with an i (Ki, Mi, Gi, Ti).
#include <cstdint>
#include <string>

namespace fenestra {

// Parses a size: a plain number of bytes, or a number with a unit k/K, M, G, T (decimal) or
// Ki, Mi, Gi, Ti (binary), optionally followed by B. Throws std::invalid_argument naming `what`.
uint64_t parse_byte_size(const std::string& text, const std::string& what = "a memory size");

// "11.5 GB", "512 MB", "3.2 kB", "17 bytes" (decimal units, three significant digits).
std::string format_bytes(double bytes);

// 1200000 -> "1 200 000"; with `significant` > 0, rounded first: (1234567, 3) -> "1 230 000".
std::string format_count(double count, int significant = 0);

}  // namespace fenestra
