#pragma once
// The opening domain: faces allowed to host openings, grouped into panels, each diced virtually
// into a grid of square elements. A flat panel is diced in its own plane; a curved one (faces
// joined along edges at less than kSmoothAngle) in its chart (surface_chart.h), so that its
// elements are patches of the surface. No geometry is modified.
#include <array>
#include <utility>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "math/vec.h"
#include "scene/cutter.h"
#include "scene/mesh.h"
#include "scene/surface_chart.h"

namespace fenestra {

// Faces meeting along an edge at less than this angle (degrees) are one curved panel.
constexpr float kSmoothAngle = 30.0f;

struct Panel {
  Vec3 origin;                  // grid corner (row 0, column 0), on the panel plane
  Vec3 u_axis, v_axis, normal;  // u along rows (horizontal on walls), v up the panel; u x v = normal
  Vec3 outward;                 // +-normal, pointing away from the sensors: where the wall's thickness lies
  // Curved panels: the chart, in which grid coordinates are chart coordinates; origin, axes and
  // normal are then the surface's at the grid corner and on average. Null on flat panels.
  std::shared_ptr<const SurfaceChart> chart;
  float chart_side = 1.0f;      // outward = chart_side * the chart's normal, on curved panels
  Vec2 parameter_lower = Vec2::Zero(), parameter_upper = Vec2::Zero();  // the faces' extent, grid coordinates
  int rows = 0, cols = 0;
  std::vector<int> grid;        // rows * cols: element index, or -1 where the cell leaves the panel
  // Grid lines in grid coordinates: cols + 1 along u, rows + 1 along v (multiples of the element
  // size).
  std::vector<float> u_lines, v_lines;
  std::vector<uint32_t> triangles;
  int material = -1;            // material of the panel's faces (reveals use it)
  std::string label;            // material and group names, for messages
  double area = 0.0;            // m^2
  float thickness = 0.0f;       // meters of wall behind the panel, along `outward` (measured or given)
  bool solid_modelled = false;  // the model has the wall's outer face (else it is added: wall_body.cpp)
  bool curved() const { return chart != nullptr; }
};

// A side face of an element's tube through a thick wall, on a grid line of its panel: between
// the cells `lower` and `upper` (elements, or -1 for the panel's margin), `normal` from lower to upper.
// Light meets one only where exactly one side is open: it is then the reveal of that opening.
struct RevealGridFace {
  int panel = 0;
  int lower = -1, upper = -1;
  Vec3 normal;
};

// A point of a panel: meters along its u and v axes from its grid corner (Panel::origin); on a
// curved panel, chart coordinates (meters along the surface).
struct PanelPoint {
  float u = 0.0f, v = 0.0f;
};

// A point of the opening domain's surface.
struct DomainSurfacePoint {
  Vec3 position;
  Vec3 outward;            // unit surface normal, away from the sensors
  float area_ratio = 1.0f;  // surface area per panel-coordinate area (1 on flat panels)
  bool on_surface = true;   // false: beyond the panel's faces (extended from the nearest one)
};

struct Element {
  int panel = 0, row = 0, col = 0;
  float u0 = 0, u1 = 0, v0 = 0, v1 = 0;  // its cell [u0, u1] x [v0, v1] in panel coordinates
  std::array<Vec3, 4> corners;  // counter-clockwise about the panel normal
  Vec3 center;
  float width() const { return u1 - u0; }
  float height() const { return v1 - v0; }
};

struct OpeningDomainSelection {
  std::vector<std::string> materials, groups;
  float element_size = 0.25f;  // meters
  // Meters of wall behind the domain faces, on the side away from the sensors. Unset: measured per
  // panel from the model (the outer face of a wall modelled as a solid), 0 where there is none.
  std::optional<float> thickness;
  SiteFrame site;  // where the mesh's local frame sits: positions in messages are the input's
};

class OpeningDomain {
 public:
  OpeningDomain() = default;
  static OpeningDomain build(const Mesh& mesh, const std::vector<std::string>& material_names,
                             const OpeningDomainSelection& selection);

  // Points each panel's `outward` away from the sensors (the wall body lies on the far side).
  void orient(const std::vector<Vec3>& sensor_points);
  // After orient(): each panel's wall thickness, measured where the model has the wall's outer
  // face, else the selection's; for a thickness the model lacks, appends the wall's outer face and
  // edge strips to `mesh`, so that the wall is the solid it will be built as (wall_body.cpp).
  // Throws std::invalid_argument when a given thickness disagrees with the modelled one.
  void build_walls(Mesh* mesh);
  // Refuses curved panels with a thickness, given or modelled: they are single surfaces.
  void check_curved_walls(const Mesh& mesh) const;
  // Side faces of the elements' tubes through thick walls, as triangles (two per face, in order).
  Mesh reveal_grid(std::vector<RevealGridFace>* faces) const;

  const std::vector<Panel>& panels() const { return panels_; }
  const std::vector<Element>& elements() const { return elements_; }
  size_t element_count() const { return elements_.size(); }
  float element_size() const { return element_size_; }
  bool has_thick_walls() const;

  // Panel of a scene triangle, or -1 when the triangle is not in the domain.
  int panel_of_triangle(size_t tri) const { return tri < triangle_panel_.size() ? triangle_panel_[tri] : -1; }
  // Panel whose wall's outer face the scene triangle is, or -1.
  int outer_panel_of_triangle(size_t tri) const { return tri < outer_panel_.size() ? outer_panel_[tri] : -1; }
  // Element containing panel point q of panel `panel`, or -1 (the panel's margin).
  int element_at(int panel, const PanelPoint& q) const;
  // Element of a panel's cell, or -1 outside the grid or where the cell leaves the panel.
  int cell(int panel, int row, int col) const;
  // The cells [first, last] along u (columns) or v (rows) that the open interval (a, b) of grid
  // coordinates overlaps (within 1e-6 of the element size); first < 0 or last >= cols (rows)
  // when it reaches beyond the grid.
  std::pair<int, int> columns_overlapping(int panel, double a, double b) const;
  std::pair<int, int> rows_overlapping(int panel, double a, double b) const;
  // Grid lines of a flat thick panel that the straight line from p (in its wall) along dir crosses
  // before it leaves the wall through its inner or outer face; a line through p is not counted.
  int lines_ahead(int panel, const Vec3& p, const Vec3& dir) const;
  // Whether x lies on one of the given grid lines (within 1e-6 of the element size).
  bool on_line(const std::vector<float>& lines, double x) const;
  // Point p of a flat panel in panel coordinates: meters along its u and v axes from its grid corner.
  PanelPoint panel_point(int panel, const Vec3& p) const {
    const Vec3 d = p - panels_[panel].origin;
    return {d.dot(panels_[panel].u_axis), d.dot(panels_[panel].v_axis)};
  }
  // Point p of scene triangle `triangle` (of panel `panel`) in panel coordinates, flat or curved.
  PanelPoint panel_point(int panel, uint32_t triangle, const Vec3& p) const {
    const SurfaceChart* chart = panels_[panel].chart.get();
    if (!chart) return panel_point(panel, p);
    const Vec2 q = chart->chart_point(triangle, p);
    return {q.x(), q.y()};
  }
  // The surface at panel point (u, v).
  DomainSurfacePoint surface_at(int panel, double u, double v) const;
  // Area of the surface per panel-coordinate area on scene triangle `triangle` of the panel.
  float area_ratio(int panel, uint32_t triangle) const {
    const SurfaceChart* chart = panels_[panel].chart.get();
    return chart ? chart->area_ratio(triangle) : 1.0f;
  }
  // The cutter that opens one element: its cell, through the wall thickness.
  Cutter element_cutter(int element) const;
  // Cutter of the panel rectangle [u0, u1] x [v0, v1].
  Cutter panel_rectangle_cutter(int panel, double u0, double u1, double v0, double v1) const;
  // Cutter of an arbitrary rectangle (corners in order) on a flat panel; throws if it lies on none.
  Cutter rectangle_cutter(const std::array<Vec3, 4>& corners, int* panel_out) const;

 private:
  std::vector<Panel> panels_;
  std::vector<Element> elements_;
  std::vector<int> triangle_panel_;
  std::vector<int> outer_panel_;
  float element_size_ = 0.25f;
  std::optional<float> given_thickness_;
};

}  // namespace fenestra
