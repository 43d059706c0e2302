#pragma once
// Open elements merged into rectangles: within each panel, greedy maximal rectangles (widest run
// along a row first, then as many rows as keep it whole), in world coordinates.
#include <cstdint>
#include <vector>

#include "scene/opening_constraints.h"
#include "scene/opening_domain.h"
#include "trace/open_region.h"

namespace fenestra {

struct OpeningRectangle {
  std::array<Vec3, 4> corners;  // counter-clockwise about the panel normal, meters (on the surface)
  Vec3 centre;
  double width = 0.0, height = 0.0;  // along the panel's u axis (horizontal on walls) and v axis
  PanelRectangle parameter;     // the same rectangle in panel coordinates (what evaluate re-reads)
  bool curved = false;          // on a curved panel: corners are not coplanar, the grid below follows it
  Vec3 outward;                 // panel normal pointing away from the sensors (through the wall); at the centre when curved
  // Curved panels: grid_rows x grid_columns points of the surface over the rectangle (row-major,
  // rows along v, edges included) and the outward unit normals there.
  int grid_rows = 0, grid_columns = 0;
  std::vector<Vec3> grid_points, grid_normals;
  double depth = 0.0;           // meters the opening cuts through along `outward`: its panel's wall thickness
  int panel = 0;
  int row0 = 0, row1 = 0, col0 = 0, col1 = 0;  // inclusive element ranges
  std::vector<int> elements;
};

// A grid rectangle of whole elements, in world coordinates.
OpeningRectangle to_world(const OpeningDomain& domain, const GridRectangle& rect);

// An opening off the grid (edges anywhere on its panel), in world coordinates; rows and columns
// span the element squares it overlaps, `elements` those whose centre it contains.
OpeningRectangle to_world(const OpeningDomain& domain, const PanelRectangle& rect);
// Elements whose centre lies in one of the openings.
std::vector<uint8_t> open_elements(const OpeningDomain& domain, const std::vector<PanelRectangle>& openings);

std::vector<OpeningRectangle> merge_into_rectangles(const OpeningDomain& domain, const std::vector<uint8_t>& open);

}  // namespace fenestra
