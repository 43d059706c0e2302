#pragma once
// Open parts of the opening domain as rectangles in panel coordinates, not only whole elements:
// what the path records evaluate when openings' edges lie between grid lines.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "scene/opening_domain.h"
#include "trace/cell_point.h"

namespace fenestra {

// [u0, u1] x [v0, v1] on a panel, meters from its grid corner (Panel::origin along u_axis, v_axis).
struct PanelRectangle {
  int panel = 0;
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  double width() const { return u1 - u0; }
  double height() const { return v1 - v0; }
  bool operator==(const PanelRectangle& o) const {
    return panel == o.panel && u0 == o.u0 && u1 == o.u1 && v0 == o.v0 && v1 == o.v1;
  }
  bool operator!=(const PanelRectangle& o) const { return !(*this == o); }
};

// An opening given by its world corners (in order around it), on the panel it lies on; throws
// std::invalid_argument when it is not a rectangle or lies on no panel.
PanelRectangle to_panel_rectangle(const OpeningDomain& domain, const std::array<Vec3, 4>& corners);

// Throws std::invalid_argument when the rectangle reaches beyond its panel's elements (into the
// margin the grid leaves, or a gap of a non-rectangular panel): paths are recorded by element, so
// light through such parts is not in the records (`evaluate` cuts them).
void check_on_elements(const OpeningDomain& domain, const PanelRectangle& rectangle);

// Whether every edge of the rectangle lies on one of its panel's grid lines.
bool edges_on_grid_lines(const OpeningDomain& domain, const PanelRectangle& rectangle);

// Throws std::invalid_argument when the rectangle lies on a thick panel with an edge between the
// lines of the grid the records were traced on: there the records follow the elements' tubes, so
// they cannot evaluate it (evaluate() cuts it; the solver traces a grid refined about such edges).
void check_on_grid_lines_in_thick_walls(const OpeningDomain& domain, const PanelRectangle& rectangle);

class OpenRegion {
 public:
  OpenRegion(const OpeningDomain& domain, const std::vector<PanelRectangle>& rectangles);
  // Whether the point where a path met element k lies in an open rectangle of k's panel. The point
  // is taken inside k's cell: crossings on its edges (stratified portal samples start at a
  // corner; tubes are crossed on grid lines) belong to k, so that rectangles on the grid open
  // exactly the elements they cover.
  bool is_open(int32_t element, const PanelPoint& p) const {
    const Cell& cell = cells_[element];
    return is_open_in(cell, std::clamp<double>(p.u, cell.u0 + inset_, cell.u1 - inset_),
                      std::clamp<double>(p.v, cell.v0 + inset_, cell.v1 - inset_));
  }
  // The same for a point of the records (where in k's cell the path met it), tested as the panel
  // point point_in_cell gives (the region search keeps those).
  bool is_open(int32_t element, const CellPoint& q) const {
    const PanelPoint p = point_in_cell(element, q);
    return is_open_in(cells_[element], p.u, p.v);
  }
  // The point is_open(element, q) tests: q's place in the element's cell, off its edges by the inset.
  PanelPoint point_in_cell(int32_t element, const CellPoint& q) const {
    const Cell& cell = cells_[element];
    double u, v;
    q.to_panel(cell.u0, cell.u1, cell.v0, cell.v1, &u, &v);
    return {static_cast<float>(std::clamp<double>(u, cell.u0 + inset_, cell.u1 - inset_)),
            static_cast<float>(std::clamp<double>(v, cell.v0 + inset_, cell.v1 - inset_))};
  }
  size_t element_count() const { return cells_.size(); }
  // The same domain's cells with other open rectangles (a search tries many).
  void set_rectangles(const std::vector<PanelRectangle>& rectangles);

 private:
  struct Cell {
    int panel;
    double u0, u1, v0, v1;  // the element's cell
  };
  std::vector<Cell> cells_;
  bool is_open_in(const Cell& cell, double u, double v) const {
    for (const PanelRectangle& r : by_panel_[cell.panel])
      if (u > r.u0 && u < r.u1 && v > r.v0 && v < r.v1) return true;
    return false;
  }

  double inset_ = 0.0;
  std::vector<std::vector<PanelRectangle>> by_panel_;
};

}  // namespace fenestra
