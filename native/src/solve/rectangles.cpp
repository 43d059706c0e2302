#include "solve/rectangles.h"

#include <algorithm>
#include <cmath>

#include <map>
#include <tuple>

namespace fenestra {
namespace {

// Step of the surface grid reported for an opening on a curved panel: at most this many meters.
constexpr double kSurfaceGridStep = 0.1;
constexpr int kMaxSurfaceGridPoints = 64;  // along each side

// The rectangle [u0, u0 + width] x [v0, v0 + height] of a panel in world coordinates.
void place(const OpeningDomain& domain, int panel_index, double u0, double v0, double width, double height,
           OpeningRectangle* r) {
  const Panel& panel = domain.panels()[panel_index];
  r->width = width;
  r->height = height;
  r->parameter = {panel_index, u0, u0 + width, v0, v0 + height};
  r->curved = panel.curved();
  r->depth = panel.thickness;
  auto at = [&](double u, double v) { return domain.surface_at(panel_index, u, v); };
  r->corners = {at(u0, v0).position, at(u0 + width, v0).position, at(u0 + width, v0 + height).position,
                at(u0, v0 + height).position};
  const DomainSurfacePoint centre = at(u0 + 0.5 * width, v0 + 0.5 * height);
  r->centre = centre.position;
  r->outward = panel.curved() ? centre.outward : panel.outward;
  r->grid_points.clear();
  r->grid_normals.clear();
  if (!panel.curved()) return;
  // Fine enough to follow the facets and the curvature: a cutter built from it follows the surface.
  const double step = std::min(kSurfaceGridStep, 0.5 * domain.element_size());
  r->grid_columns = std::clamp(static_cast<int>(std::ceil(width / step)), 1, kMaxSurfaceGridPoints - 1) + 1;
  r->grid_rows = std::clamp(static_cast<int>(std::ceil(height / step)), 1, kMaxSurfaceGridPoints - 1) + 1;
  for (int i = 0; i < r->grid_rows; ++i)
    for (int j = 0; j < r->grid_columns; ++j) {
      const DomainSurfacePoint p =
          at(u0 + width * j / (r->grid_columns - 1), v0 + height * i / (r->grid_rows - 1));
      r->grid_points.push_back(p.position);
      r->grid_normals.push_back(p.outward);
    }
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
  place(domain, rect.panel, rect.col0 * a, rect.row0 * a, rect.cols() * a, rect.rows() * a, &r);
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
  place(domain, rect.panel, rect.u0, rect.v0, rect.width(), rect.height(), &r);
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
