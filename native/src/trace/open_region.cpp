#include "trace/open_region.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace fenestra {

PanelRectangle to_panel_rectangle(const OpeningDomain& domain, const std::array<Vec3, 4>& corners) {
  int panel = -1;
  domain.rectangle_cutter(corners, &panel);  // checks the rectangle and finds its panel
  PanelRectangle r{panel, 1e300, -1e300, 1e300, -1e300};
  for (const Vec3& c : corners) {
    const PanelPoint q = domain.panel_point(panel, c);
    r.u0 = std::min<double>(r.u0, q.u), r.u1 = std::max<double>(r.u1, q.u);
    r.v0 = std::min<double>(r.v0, q.v), r.v1 = std::max<double>(r.v1, q.v);
  }
  return r;
}

OpenRegion::OpenRegion(const OpeningDomain& domain, const std::vector<PanelRectangle>& rectangles)
    : by_panel_(domain.panels().size()) {
  size_ = domain.element_size();
  inset_ = 1e-5 * size_;  // far above float rounding of panel coordinates, far below any edge step
  cells_.reserve(domain.element_count());
  for (const Element& e : domain.elements()) cells_.push_back({e.panel, e.col * size_, e.row * size_});
  for (const PanelRectangle& r : rectangles) {
    if (r.panel < 0 || static_cast<size_t>(r.panel) >= by_panel_.size())
      throw std::invalid_argument("open rectangle on panel " + std::to_string(r.panel) + ", which does not exist");
    by_panel_[r.panel].push_back(r);
  }
}

}  // namespace fenestra
