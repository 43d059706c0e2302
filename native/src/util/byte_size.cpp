#include "util/byte_size.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include "util/decimal_number.h"
#include "util/quoted_text.h"

namespace fenestra {

uint64_t parse_byte_size(const std::string& text, const std::string& what) {
  auto fail = [&]() -> uint64_t {
    throw std::invalid_argument(what + " expects a size in bytes such as 8G, 512M, 1.5GB or 2GiB, got '" +
                                quoted_text(text) + "'");
  };
  // The unit is the trailing letters; the rest must be a plain decimal number.
  std::size_t split = text.size();
  while (split > 0 && std::isalpha(static_cast<unsigned char>(text[split - 1]))) --split;
  if (!is_decimal_number(std::string_view(text).substr(0, split), false)) return fail();
  const double number = std::strtod(text.substr(0, split).c_str(), nullptr);
  std::string unit = text.substr(split);
  if (!unit.empty() && (unit.back() == 'B' || unit.back() == 'b')) unit.pop_back();
  double scale = 1.0;
  if (!unit.empty()) {
    const bool binary = unit.size() == 2 && unit[1] == 'i';
    if (unit.size() != 1 && !binary) return fail();
    const size_t power = std::string("kmgt").find(static_cast<char>(std::tolower(static_cast<unsigned char>(unit[0]))));
    if (power == std::string::npos) return fail();
    scale = std::pow(binary ? 1024.0 : 1000.0, static_cast<double>(power + 1));
  }
  const double bytes = number * scale;
  if (!std::isfinite(bytes) || bytes < 1.0 || bytes > 9.2e18) return fail();
  return static_cast<uint64_t>(bytes);
}

std::string format_bytes(double bytes) {
  static const char* kUnits[] = {"kB", "MB", "GB", "TB", "PB", "EB"};
  if (!(bytes >= 1000.0)) return std::to_string(static_cast<long long>(std::max(0.0, bytes))) + " bytes";
  int unit = 0;
  double v = bytes / 1000.0;
  while (v >= 999.5 && unit < 5) v /= 1000.0, ++unit;
  char buf[64];
  std::snprintf(buf, sizeof buf, v < 99.95 ? "%.1f %s" : "%.0f %s", v, kUnits[unit]);
  return buf;
}

std::string format_count(double count, int significant) {
  if (!(count < 9.2e18)) return "more than 9 200 000 000 000 000 000";
  if (significant > 0 && count >= 1.0) {
    const double unit = std::pow(10.0, std::floor(std::log10(count)) + 1 - significant);
    if (unit > 1.0) count = std::round(count / unit) * unit;
  }
  std::string digits = std::to_string(static_cast<unsigned long long>(std::max(0.0, std::round(count))));
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3) digits.insert(static_cast<size_t>(i), " ");
  return digits;
}

}  // namespace fenestra
