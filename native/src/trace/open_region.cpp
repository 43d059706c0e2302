#include "trace/open_region.h"

#include <algorithm>
#include <cmath>
#include <sstream>
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

void check_on_elements(const OpeningDomain& domain, const PanelRectangle& r) {
  const Panel& panel = domain.panels().at(r.panel);
  const auto [c0, c1] = domain.columns_overlapping(r.panel, r.u0, r.u1);
  const auto [r0, r1] = domain.rows_overlapping(r.panel, r.v0, r.v1);
  bool covered = c0 <= c1 && r0 <= r1;
  for (int row = r0; row <= r1 && covered; ++row)
    for (int col = c0; col <= c1 && covered; ++col) covered = domain.cell(r.panel, row, col) >= 0;
  if (covered) return;
  std::ostringstream m;
  m << "reaches beyond the elements of panel " << r.panel << " (" << panel.label << "; its grid spans u 0.." << panel.u_lines.back()
    << " m, v 0.." << panel.v_lines.back() << " m): paths are recorded by element, so the exact evaluation cannot count "
    << "light through the panel's margin; evaluate() traces it";
  throw std::invalid_argument(m.str());
}

bool edges_on_grid_lines(const OpeningDomain& domain, const PanelRectangle& r) {
  const Panel& panel = domain.panels().at(r.panel);
  return domain.on_line(panel.u_lines, r.u0) && domain.on_line(panel.u_lines, r.u1) &&
         domain.on_line(panel.v_lines, r.v0) && domain.on_line(panel.v_lines, r.v1);
}

void check_on_grid_lines_in_thick_walls(const OpeningDomain& domain, const PanelRectangle& r) {
  const Panel& panel = domain.panels().at(r.panel);
  if (!(panel.thickness > 0.0f) || edges_on_grid_lines(domain, r)) return;
  std::ostringstream m;
  m << "has an edge between the element grid's lines (u " << r.u0 << ".." << r.u1 << " m, v " << r.v0 << ".." << r.v1
    << " m; lines every " << domain.element_size() << " m) on panel " << r.panel << " (" << panel.label
    << "), whose wall is " << panel.thickness << " m thick: there the records follow the elements' tubes through "
    << "the wall and cannot count it; evaluate() cuts it";
  throw std::invalid_argument(m.str());
}

OpenRegion::OpenRegion(const OpeningDomain& domain, const std::vector<PanelRectangle>& rectangles)
    : by_panel_(domain.panels().size()) {
  inset_ = 1e-5 * domain.element_size();  // far above float rounding of panel coordinates, far below any edge step
  cells_.reserve(domain.element_count());
  for (const Element& e : domain.elements()) cells_.push_back({e.panel, e.u0, e.u1, e.v0, e.v1});
  set_rectangles(rectangles);
}

void OpenRegion::set_rectangles(const std::vector<PanelRectangle>& rectangles) {
  for (std::vector<PanelRectangle>& list : by_panel_) list.clear();
  for (const PanelRectangle& r : rectangles) {
    if (r.panel < 0 || static_cast<size_t>(r.panel) >= by_panel_.size())
      throw std::invalid_argument("open rectangle on panel " + std::to_string(r.panel) + ", which does not exist");
    by_panel_[r.panel].push_back(r);
  }
}

}  // namespace fenestra
