#include "scene/window_catalogue.h"

#include <cmath>
#include <stdexcept>

#include "scene/facades.h"

namespace fenestra {
namespace {

std::vector<CatalogueSize> grid_of(const std::vector<double>& widths, const std::vector<double>& heights) {
  std::vector<CatalogueSize> sizes;
  for (double w : widths)
    for (double h : heights) sizes.push_back({w, h});
  return sizes;
}

}  // namespace

std::vector<CatalogueSize> WindowCatalogue::sizes_for(const Panel& panel) const {
  if (is_wall(panel)) return walls;
  std::vector<CatalogueSize> sizes = roofs;
  for (const CatalogueSize& s : roofs)
    if (s.width != s.height) sizes.push_back({s.height, s.width});
  return sizes;
}

bool WindowCatalogue::allows(const Panel& panel, double width, double height) const {
  const std::vector<CatalogueSize>& list = is_wall(panel) ? walls : roofs;
  if (list.empty()) return true;
  auto same = [](double a, double b) { return std::abs(a - b) <= kCatalogueSizeTolerance; };
  for (const CatalogueSize& s : list) {
    if (same(s.width, width) && same(s.height, height)) return true;
    if (!is_wall(panel) && same(s.height, width) && same(s.width, height)) return true;
  }
  return false;
}

std::vector<std::string> catalogue_names() { return {"residential", "commercial"}; }

WindowCatalogue builtin_catalogue(const std::string& name) {
  WindowCatalogue c;
  c.name = name;
  if (name == "residential") {
    c.walls = grid_of({0.6, 0.9, 1.2, 1.5, 1.8}, {1.2, 1.5, 2.1});
    // Common roof-window sizes (width x length down the slope).
    c.roofs = {{0.55, 0.78}, {0.55, 0.98}, {0.66, 1.18}, {0.78, 0.98}, {0.78, 1.18},
               {0.78, 1.40}, {0.94, 1.18}, {1.14, 1.18}, {1.34, 0.98}, {1.34, 1.40}};
    return c;
  }
  if (name == "commercial") {
    c.walls = grid_of({1.2, 1.5, 1.8, 2.4, 3.0}, {1.5, 1.8, 2.4});
    c.roofs = grid_of({1.2, 1.8, 2.4}, {1.2, 1.8, 2.4});
    return c;
  }
  std::string names;
  for (const std::string& n : catalogue_names()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("no built-in catalogue '" + name + "' (there are: " + names + ")");
}

}  // namespace fenestra
