#pragma once
// When a study needs too much memory because of its element count, the refusal names the element
// size that would fit, rounded up to a size one would type: "use a larger element_size (0.05 m or
// more: ...)", rather than leaving the user to guess by trial and refusal.
#include <functional>
#include <string>

namespace fenestra {

// What the refusals name as the setting to change when the elements are too many.
inline constexpr const char* kLargerElementSize = "a larger element_size (opening_domain.element_size or solver.element_size)";

// The smallest element size, rounded up (to centimetres below 0.2 m, to 5 cm below 1 m, to 10 cm
// above), at which `elements` at `element_size` become few enough (count ~ 1 / size^2) that
// bytes_for(count) <= limit_bytes and count <= max_elements; 0 when even one element does not fit.
// bytes_for must grow with the count.
double element_size_that_fits(double element_size, double elements, const std::function<double(double)>& bytes_for,
                              double limit_bytes, double max_elements);

// kLargerElementSize with the size that fits: "a larger element_size (0.05 m or more:
// opening_domain.element_size or solver.element_size)"; kLargerElementSize when `fits` is 0.
std::string larger_element_size(double fits);

}  // namespace fenestra
