#pragma once
// Numbers in Fenestra's messages, written one way wherever they appear.
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <string>

namespace fenestra {

// As a stream writes it, to `precision` significant digits (6: "0.25", "1e+07").
inline std::string decimal_text(double v, int precision = 6) {
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

// With a printf format for one double ("%.2f", "%.3g").
inline std::string decimal_text(double v, const char* format) {
  char text[48];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

// A fraction as a percentage to one decimal: 0.553 -> "55.3 %".
inline std::string percent_text(double fraction) { return decimal_text(100.0 * fraction, "%.1f") + " %"; }

// A fraction as a percentage rounded to one decimal, trailing zeros dropped: 0.55 -> "55 %".
inline std::string short_percent_text(double fraction) {
  return decimal_text(std::round(1000.0 * fraction) / 10.0, "%g") + " %";
}

}  // namespace fenestra
