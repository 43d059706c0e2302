#pragma once
// Where a path met an element, kept in its records: the point's place in the element's cell as
// fractions of the cell's width and height in steps of 1/65535. Four bytes instead of a panel
// point's eight; rounded by at most half a step (2.3 micrometres on a 0.3 m element), far below
// anything an opening's edge is placed by, and symmetric, so a rectangle's edge between grid lines
// sees as many points moved in as out.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "scene/opening_domain.h"  // Element, PanelPoint

namespace fenestra {

struct CellPoint {
  uint16_t s = 0, t = 0;

  static constexpr float kSteps = 65535.0f;

  // p, taken inside the cell [u0, u1] x [v0, v1] (points on or just past its edges belong to it).
  static CellPoint in_cell(const PanelPoint& p, float u0, float u1, float v0, float v1) {
    return {fraction(p.u, u0, u1), fraction(p.v, v0, v1)};
  }
  static CellPoint of(const Element& cell, const PanelPoint& p) { return in_cell(p, cell.u0, cell.u1, cell.v0, cell.v1); }

  // The panel point it stands for, in the cell [u0, u1] x [v0, v1].
  template <typename Real>
  void to_panel(Real u0, Real u1, Real v0, Real v1, Real* u, Real* v) const {
    *u = u0 + (u1 - u0) * static_cast<Real>(s) / static_cast<Real>(kSteps);
    *v = v0 + (v1 - v0) * static_cast<Real>(t) / static_cast<Real>(kSteps);
  }

 private:
  static uint16_t fraction(float x, float lo, float hi) {
    const float f = hi > lo ? (x - lo) / (hi - lo) : 0.0f;
    if (!(f > 0.0f)) return 0;  // NaN too
    return static_cast<uint16_t>(std::lround(std::min(f, 1.0f) * kSteps));
  }
};

}  // namespace fenestra
