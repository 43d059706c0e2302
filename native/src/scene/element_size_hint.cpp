#include "scene/element_size_hint.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fenestra {
namespace {

// The steps sizes are typed in: centimetres below 0.2 m, 5 cm below 1 m, 10 cm above.
double step_at(double size) { return size < 0.2 - 1e-9 ? 0.01 : size < 1.0 - 1e-9 ? 0.05 : 0.1; }
double round_up_to_step(double size) {
  const double step = step_at(size);
  return std::round(std::ceil(size / step - 1e-9) * step * 1e6) / 1e6;
}

}  // namespace

double element_size_that_fits(double element_size, double elements, const std::function<double(double)>& bytes_for,
                              double limit_bytes, double max_elements) {
  if (!(element_size > 0.0) || !(elements > 0.0)) return 0.0;
  const auto fits = [&](double count) {
    return count <= max_elements * (1.0 + 1e-9) && bytes_for(count) <= limit_bytes;
  };
  const auto count_at = [&](double size) { return elements * (element_size / size) * (element_size / size); };
  if (!fits(1.0)) return 0.0;
  if (fits(elements)) return element_size;
  double lo = 1.0, hi = elements;  // fits(lo), not fits(hi)
  for (int i = 0; i < 200 && hi - lo > 1e-6 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (fits(mid) ? lo : hi) = mid;
  }
  double size = round_up_to_step(element_size * std::sqrt(elements / lo));
  for (;;) {  // the search stops short of the exact count: the step below may fit too
    const double below = std::round((size - step_at(size - 1e-9)) * 1e6) / 1e6;
    if (below <= element_size || !fits(count_at(below))) break;
    size = below;
  }
  while (!fits(count_at(size))) size = round_up_to_step(size + 0.5 * step_at(size));
  return size;
}

std::string larger_element_size(double fits) {
  if (!(fits > 0.0)) return kLargerElementSize;
  std::ostringstream s;
  s << "a larger element_size (" << fits << " m or more: opening_domain.element_size or solver.element_size)";
  return s.str();
}

}  // namespace fenestra
