#include "trace/open_region.h"

#include <stdexcept>
#include <string>

namespace fenestra {

OpenRegion::OpenRegion(const OpeningDomain& domain, const std::vector<PanelRectangle>& rectangles)
    : by_panel_(domain.panels().size()) {
  element_panel_.reserve(domain.element_count());
  for (const Element& e : domain.elements()) element_panel_.push_back(e.panel);
  for (const PanelRectangle& r : rectangles) {
    if (r.panel < 0 || static_cast<size_t>(r.panel) >= by_panel_.size())
      throw std::invalid_argument("open rectangle on panel " + std::to_string(r.panel) + ", which does not exist");
    by_panel_[r.panel].push_back(r);
  }
}

}  // namespace fenestra
