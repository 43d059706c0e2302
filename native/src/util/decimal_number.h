#pragma once
// The one form of number Fenestra reads from text outside JSON (OBJ coordinates, sizes such as
// --max-memory): std::strtod alone also reads "0x10" (as 16), "inf", "nan" and "1e" (as 1).
#include <cctype>
#include <string_view>

namespace fenestra {

// An optional sign, digits with an optional fraction (at least one digit in all), and an optional
// exponent: "-1.5", "2.", ".5", "3e-4". With `sign` false, no leading sign.
inline bool is_decimal_number(std::string_view text, bool sign = true) {
  std::size_t i = 0;
  auto digits = [&] {
    const std::size_t from = i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i;
    return i - from;
  };
  if (sign && i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  std::size_t mantissa = digits();
  if (i < text.size() && text[i] == '.') ++i, mantissa += digits();
  if (mantissa == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (digits() == 0) return false;
  }
  return i == text.size();
}

}  // namespace fenestra
