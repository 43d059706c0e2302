#include "solve/rectangles.h"

#include <cmath>

#include <map>
#include <tuple>

namespace fenestra {
namespace {

// The rectangle [u0, u0 + width] x [v0, v0 + height] of a panel in world coordinates.
void place(const Panel& panel, double u0, double v0, double width, double height, OpeningRectangle* r) {
  const Vec3 base = panel.origin + static_cast<float>(u0) * panel.u_axis + static_cast<float>(v0) * panel.v_axis;
  r->width = width;
  r->height = height;
  const Vec3 u = static_cast<float>(width) * panel.u_axis, v = static_cast<float>(height) * panel.v_axis;
  r->corners = {base, base + u, base + u + v, base + v};
  r->centre = base + 0.5f * (u + v);
  r->outward = panel.outward;
  r->depth = panel.thickness;
}

}  // namespace

OpeningRectangle to_world(const OpeningDomain& domain, const GridRectangle& rect) {
  const Panel& panel = domain.panels()[rect.panel];
  OpeningRectangle r;
  r.panel = rect.panel;
  r.row0 = rect.row0;
  r.row1 = rect.row1;
  r.col0 = rect.col0;
  r.col1 = rect.col1;
  for (int row = rect.row0; row <= rect.row1; ++row)
    for (int col = rect.col0; col <= rect.col1; ++col) r.elements.push_back(panel.grid[row * panel.cols + col]);
  const double a = domain.element_size();
  place(panel, rect.col0 * a, rect.row0 * a, rect.cols() * a, rect.rows() * a, &r);
  return r;
}

OpeningRectangle to_world(const OpeningDomain& domain, const PanelRectangle& rect) {
  const Panel& panel = domain.panels()[rect.panel];
  const double a = domain.element_size();
  OpeningRectangle r;
  r.panel = rect.panel;
  r.col0 = static_cast<int>(std::floor(rect.u0 / a + 1e-6));
  r.col1 = static_cast<int>(std::ceil(rect.u1 / a - 1e-6)) - 1;
  r.row0 = static_cast<int>(std::floor(rect.v0 / a + 1e-6));
  r.row1 = static_cast<int>(std::ceil(rect.v1 / a - 1e-6)) - 1;
  for (int row = std::max(0, r.row0); row <= std::min(panel.rows - 1, r.row1); ++row)
    for (int col = std::max(0, r.col0); col <= std::min(panel.cols - 1, r.col1); ++col) {
      const int k = panel.grid[static_cast<size_t>(row) * panel.cols + col];
      const double cu = (col + 0.5) * a, cv = (row + 0.5) * a;
      if (k >= 0 && cu > rect.u0 && cu < rect.u1 && cv > rect.v0 && cv < rect.v1) r.elements.push_back(k);
    }
  place(panel, rect.u0, rect.v0, rect.width(), rect.height(), &r);
  return r;
}

std::vector<uint8_t> open_elements(const OpeningDomain& domain, const std::vector<PanelRectangle>& openings) {
  std::vector<uint8_t> open(domain.element_count(), 0);
  for (const PanelRectangle& r : openings)
    for (int k : to_world(domain, r).elements) open[k] = 1;
  return open;
}

std::vector<OpeningRectangle> merge_into_rectangles(const OpeningDomain& domain, const std::vector<uint8_t>& open) {
  const auto& elements = domain.elements();
  std::map<std::tuple<int, int, int>, int> index;  // (panel, row, col) -> element
  for (size_t k = 0; k < elements.size(); ++k)
    if (open[k]) index[{elements[k].panel, elements[k].row, elements[k].col}] = static_cast<int>(k);
  auto free_at = [&](int panel, int row, int col) {
    const auto it = index.find({panel, row, col});
    return it == index.end() ? -1 : it->second;
  };
  std::vector<OpeningRectangle> out;
  while (!index.empty()) {
    // The first free element in (panel, row, col) order starts a rectangle.
    const auto [panel, row0, col0] = index.begin()->first;
    int col1 = col0;
    while (free_at(panel, row0, col1 + 1) >= 0) ++col1;
    int row1 = row0;
    for (;;) {
      bool whole = true;
      for (int c = col0; c <= col1 && whole; ++c) whole = free_at(panel, row1 + 1, c) >= 0;
      if (!whole) break;
      ++row1;
    }
    for (int rr = row0; rr <= row1; ++rr)
      for (int c = col0; c <= col1; ++c) index.erase({panel, rr, c});
    out.push_back(to_world(domain, GridRectangle{panel, row0, row1, col0, col1}));
  }
  return out;
}

}  // namespace fenestra
