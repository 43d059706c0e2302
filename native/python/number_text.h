#pragma once
// A number as Python shows it in a message (nan, inf, 1e+300), not std::to_string's 300 digits.
#include <cmath>
#include <sstream>
#include <string>

namespace fenestra {

inline std::string number_text(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace fenestra
