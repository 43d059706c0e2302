#pragma once
// A panel's axes in its plane, from its normal: rows run level on walls and tilted roofs (u
// horizontal), flat roofs take +X as their row direction; v = n x u runs up the panel.
#include <cmath>

namespace fenestra {

// V: an Eigen 3-vector, float (the opening domain) or double (curved surfaces' charts).
template <typename V>
void panel_axes(const V& n, V* u, V* v) {
  using S = typename V::Scalar;
  if (std::abs(n.z()) < static_cast<S>(0.999)) {
    *u = V(0, 0, 1).cross(n).normalized();
  } else {
    *u = (V(1, 0, 0) - n.x() * n).normalized();
  }
  *v = n.cross(*u);
}

}  // namespace fenestra
