#include "scene/opening_domain.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "math/panel_axes.h"
#include "scene/domain_estimate.h"
#include "scene/position_key.h"
#include "scene/surface_chart.h"

namespace fenestra {
namespace {

constexpr float kPlaneTolerance = 1e-3f;   // meters: faces this close to one plane are coplanar
constexpr float kNormalTolerance = 1e-4f;  // 1 - cos of the angle between coplanar normals

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

struct Triangle2D {
  Vec2 a, b, c;
  bool contains(const Vec2& p, float eps) const {
    auto edge = [](const Vec2& p0, const Vec2& p1, const Vec2& q) {
      return (p1.x() - p0.x()) * (q.y() - p0.y()) - (p1.y() - p0.y()) * (q.x() - p0.x());
    };
    const float area = edge(a, b, c);
    const float s = area < 0 ? -1.0f : 1.0f;
    const float scale = std::abs(area);
    return s * edge(a, b, p) >= -eps * scale && s * edge(b, c, p) >= -eps * scale &&
           s * edge(c, a, p) >= -eps * scale;
  }
};

// Triangles sharing an edge whose UVs, where both have them, agree along it (a UV seam parts the
// surface; a face without UVs beside one with them stays joined, and its chart is refused).
bool smoothly_joined(const Mesh& mesh, uint32_t a, uint32_t b) {
  int shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (position_key(mesh.vertex(a, i)) != position_key(mesh.vertex(b, j))) continue;
      if (mesh.has_uv(a) && mesh.has_uv(b) && (mesh.uv(a, i) - mesh.uv(b, j)).norm() > 1e-6f) return false;
      ++shared;
    }
  return shared == 2;
}

bool is_flat(const Mesh& mesh, const std::vector<uint32_t>& tris) {
  const Vec3 n0 = mesh.area_normal(tris.front()).normalized();
  const Vec3 p0 = mesh.vertex(tris.front(), 0);
  for (uint32_t t : tris) {
    if (mesh.area_normal(t).normalized().dot(n0) < 1.0f - kNormalTolerance) return false;
    for (int k = 0; k < 3; ++k)
      if (std::abs(n0.dot(mesh.vertex(t, k) - p0)) > kPlaneTolerance) return false;
  }
  return true;
}

std::string describe_panel(const Mesh& mesh, const std::vector<std::string>& material_names,
                           const std::vector<uint32_t>& tris) {
  const uint32_t t = tris.front();
  std::string label = "material '" + material_names[mesh.triangle_material[t]] + "'";
  if (mesh.triangle_group[t] >= 0) label += ", group '" + mesh.group_names[mesh.triangle_group[t]] + "'";
  return label;
}

// A curved panel's origin and axes: the surface's at the grid corner, its axes the directions of
// the chart's u and v there (v vertical on a wall whose rulings are).
void place_on_chart(Panel* panel, float element_size) {
  const SurfaceChart& chart = *panel->chart;
  const Vec2 centre = 0.5f * Vec2(panel->cols * element_size, panel->rows * element_size);
  const Vec3 c = chart.surface_point(centre).position;
  const float h = element_size;
  const Vec3 du = chart.surface_point(centre + Vec2(h, 0)).position - c;
  const Vec3 dv = chart.surface_point(centre + Vec2(0, h)).position - c;
  if (du.norm() > 1e-6f && dv.norm() > 1e-6f) {
    panel->u_axis = du.normalized();
    panel->v_axis = (dv - dv.dot(panel->u_axis) * panel->u_axis).normalized();
  }
  panel->origin = chart.surface_point(Vec2::Zero()).position;
}

}  // namespace

OpeningDomain OpeningDomain::build(const Mesh& mesh, const std::vector<std::string>& material_names,
                                   const OpeningDomainSelection& sel) {
  if (!(sel.element_size > 0.0f) || !std::isfinite(sel.element_size))
    throw std::invalid_argument("opening_domain.element_size must be a positive number of meters");
  if (sel.thickness && (!(*sel.thickness >= 0.0f) || !std::isfinite(*sel.thickness)))
    throw std::invalid_argument("opening_domain.thickness must be a non-negative number of meters");
  for (const auto& name : sel.materials)
    if (std::find(material_names.begin(), material_names.end(), name) == material_names.end())
      throw std::invalid_argument("opening_domain.materials lists '" + name + "', which is not a defined material");
  for (const auto& name : sel.groups)
    if (std::find(mesh.group_names.begin(), mesh.group_names.end(), name) == mesh.group_names.end())
      throw std::invalid_argument("opening_domain.groups lists '" + name + "', which is no group (g/o) of the geometry");

  auto selected = [&](size_t t) {
    const std::string& m = material_names[mesh.triangle_material[t]];
    if (std::find(sel.materials.begin(), sel.materials.end(), m) != sel.materials.end()) return true;
    const int g = mesh.triangle_group[t];
    return g >= 0 && std::find(sel.groups.begin(), sel.groups.end(), mesh.group_names[g]) != sel.groups.end();
  };

  OpeningDomain domain;
  domain.element_size_ = sel.element_size;
  domain.given_thickness_ = sel.thickness;
  domain.triangle_panel_.assign(mesh.triangle_count(), -1);

  std::vector<uint32_t> tris;
  for (size_t t = 0; t < mesh.triangle_count(); ++t)
    if (selected(t)) tris.push_back(static_cast<uint32_t>(t));
  if (tris.empty())
    throw std::invalid_argument("the opening domain is empty: no face has a material or group listed in \"opening_domain\"");

  // Coplanar faces sharing a vertex position form one panel; so do faces sharing an edge at a
  // small angle (a curved surface), where their UVs, if any, continue across it.
  std::vector<Vec3> unit_normal(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) unit_normal[i] = mesh.area_normal(tris[i]).normalized();
  UnionFind uf(tris.size());
  std::unordered_map<uint64_t, std::vector<int>> by_vertex;
  for (size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) by_vertex[position_key(mesh.vertex(tris[i], k))].push_back(static_cast<int>(i));
  const float smooth_cos = std::cos(kSmoothAngle * kPi / 180.0f);
  for (const auto& entry : by_vertex) {
    const auto& list = entry.second;
    for (size_t a = 0; a < list.size(); ++a)
      for (size_t b = a + 1; b < list.size(); ++b) {
        const int i = list[a], j = list[b];
        const float cos = unit_normal[i].dot(unit_normal[j]);
        const bool coplanar = cos >= 1.0f - kNormalTolerance &&
                              std::abs(unit_normal[i].dot(mesh.vertex(tris[j], 0) - mesh.vertex(tris[i], 0))) <= kPlaneTolerance;
        if (coplanar || (std::abs(cos) >= smooth_cos && smoothly_joined(mesh, tris[i], tris[j]))) uf.unite(i, j);
      }
  }
  std::vector<std::vector<uint32_t>> components;
  std::unordered_map<int, int> component_of_root;
  for (size_t i = 0; i < tris.size(); ++i) {
    const int root = uf.find(static_cast<int>(i));
    auto it = component_of_root.find(root);
    if (it == component_of_root.end()) {
      it = component_of_root.emplace(root, static_cast<int>(components.size())).first;
      components.emplace_back();
    }
    components[it->second].push_back(tris[i]);
  }

  // The element count, estimated from the panels' areas, must fit before any grid is allocated.
  check_domain_cost(estimate_domain(mesh, components, sel.element_size), sel.element_size);
  const float s = sel.element_size;
  for (const auto& comp : components) {
    Panel panel;
    panel.triangles = comp;
    panel.material = mesh.triangle_material[comp.front()];
    panel.label = describe_panel(mesh, material_names, comp);
    const bool curved = !is_flat(mesh, comp);
    std::shared_ptr<SurfaceChart> chart;
    if (curved) chart = std::make_shared<SurfaceChart>(SurfaceChart::build(mesh, comp, panel.label, sel.site));
    Vec3 n = Vec3::Zero();
    double area = 0.0;
    for (size_t i = 0; i < comp.size(); ++i) {
      const Vec3 an = mesh.area_normal(comp[i]);
      area += 0.5 * an.norm();
      n += chart ? 0.5f * an.norm() * chart->chart_normal(comp[i]) : an;
    }
    panel.area = area;
    n = n.norm() > 1e-6f * static_cast<float>(area) ? Vec3(n.normalized()) : mesh.area_normal(comp.front()).normalized();
    panel.normal = n;
    panel.outward = n;
    panel_axes(n, &panel.u_axis, &panel.v_axis);

    // The faces flat in panel coordinates: the panel's plane, or the chart.
    const Vec3 o = mesh.vertex(comp.front(), 0);
    std::vector<Triangle2D> flat;
    float amin = 1e30f, amax = -1e30f, bmin = 1e30f, bmax = -1e30f;
    for (size_t i = 0; i < comp.size(); ++i) {
      Vec2 q[3];
      for (int k = 0; k < 3; ++k) {
        const Vec3 d = mesh.vertex(comp[i], k) - o;
        q[k] = chart ? chart->flat(i)[k] : Vec2(d.dot(panel.u_axis), d.dot(panel.v_axis));
        amin = std::min(amin, q[k].x()), amax = std::max(amax, q[k].x());
        bmin = std::min(bmin, q[k].y()), bmax = std::max(bmax, q[k].y());
      }
      flat.push_back({q[0], q[1], q[2]});
    }
    const float width = amax - amin, height = bmax - bmin;
    panel.cols = static_cast<int>(std::floor(width / s + 1e-4f));
    panel.rows = static_cast<int>(std::floor(height / s + 1e-4f));
    // Centre the grid so leftover margins are equal on both sides.
    const float a0 = amin + 0.5f * (width - panel.cols * s);
    const float b0 = bmin + 0.5f * (height - panel.rows * s);
    panel.parameter_lower = Vec2(amin - a0, bmin - b0);
    panel.parameter_upper = Vec2(amax - a0, bmax - b0);
    if (chart) {
      chart->translate(Vec2(-a0, -b0));
      panel.chart = chart;
      place_on_chart(&panel, s);
    } else {
      panel.origin = o + a0 * panel.u_axis + b0 * panel.v_axis;
    }

    const int panel_index = static_cast<int>(domain.panels_.size());
    panel.grid.assign(static_cast<size_t>(panel.rows) * panel.cols, -1);
    auto inside = [&](const Vec2& p) {
      if (chart) return chart->contains(p - Vec2(a0, b0));
      for (const auto& tri : flat)
        if (tri.contains(p, 1e-5f)) return true;
      return false;
    };
    for (int r = 0; r < panel.rows; ++r)
      for (int c = 0; c < panel.cols; ++c) {
        bool all_inside = true;
        for (int i = 0; i < 3 && all_inside; ++i)
          for (int j = 0; j < 3 && all_inside; ++j) {
            const float fa = 0.001f + 0.499f * i, fb = 0.001f + 0.499f * j;
            all_inside = inside(Vec2(a0 + (c + fa) * s, b0 + (r + fb) * s));
          }
        if (!all_inside) continue;
        Element e;
        e.panel = panel_index;
        e.row = r;
        e.col = c;
        auto at = [&](float u, float v) {
          return chart ? chart->surface_point(Vec2(u, v)).position : Vec3(panel.origin + u * panel.u_axis + v * panel.v_axis);
        };
        e.u0 = c * s, e.v0 = r * s, e.u1 = e.u0 + s, e.v1 = e.v0 + s;
        e.corners = {at(e.u0, e.v0), at(e.u1, e.v0), at(e.u1, e.v1), at(e.u0, e.v1)};
        e.center = at(e.u0 + 0.5f * s, e.v0 + 0.5f * s);
        panel.grid[static_cast<size_t>(r) * panel.cols + c] = static_cast<int>(domain.elements_.size());
        domain.elements_.push_back(e);
      }
    for (int c = 0; c <= panel.cols; ++c) panel.u_lines.push_back(c * s);
    for (int r = 0; r <= panel.rows; ++r) panel.v_lines.push_back(r * s);
    bool any = std::any_of(panel.grid.begin(), panel.grid.end(), [](int e) { return e >= 0; });
    if (!any) {
      std::ostringstream m;
      m << "opening_domain.element_size " << s << " m is larger than the opening-domain panel of " << panel.label
        << " (" << width << " m x " << height << " m): no element fits";
      throw std::invalid_argument(m.str());
    }
    for (uint32_t t : comp) domain.triangle_panel_[t] = panel_index;
    domain.panels_.push_back(std::move(panel));
  }
  return domain;
}

void OpeningDomain::orient(const std::vector<Vec3>& sensor_points) {
  for (size_t index = 0; index < panels_.size(); ++index) {
    Panel& panel = panels_[index];
    double side = 0.0;
    if (!panel.curved()) {
      for (const Vec3& p : sensor_points) side += (p - panel.origin).dot(panel.normal) > 0.0f ? 1.0 : -1.0;
    } else {  // sensors vote at up to 16 of the panel's elements, against the local normal
      std::vector<const Element*> own;
      for (const Element& e : elements_)
        if (e.panel == static_cast<int>(index)) own.push_back(&e);
      const size_t step = std::max<size_t>(1, own.size() / 16);
      for (size_t i = 0; i < own.size(); i += step) {
        const SurfaceChart::SurfacePoint at = panel.chart->surface_point(
            Vec2(0.5f * (own[i]->u0 + own[i]->u1), 0.5f * (own[i]->v0 + own[i]->v1)));
        for (const Vec3& p : sensor_points) side += (p - at.position).dot(at.normal) > 0.0f ? 1.0 : -1.0;
      }
    }
    panel.chart_side = side > 0.0 ? -1.0f : 1.0f;
    panel.outward = side > 0.0 ? Vec3(-panel.normal) : panel.normal;
  }
}

DomainSurfacePoint OpeningDomain::surface_at(int panel_index, double u, double v) const {
  const Panel& panel = panels_[panel_index];
  DomainSurfacePoint out;
  if (!panel.curved()) {
    out.position = panel.origin + static_cast<float>(u) * panel.u_axis + static_cast<float>(v) * panel.v_axis;
    out.outward = panel.outward;
    const Vec2 q(static_cast<float>(u), static_cast<float>(v));
    out.on_surface = (q.array() >= panel.parameter_lower.array() - 1e-4f).all() &&
                     (q.array() <= panel.parameter_upper.array() + 1e-4f).all();
    return out;
  }
  const SurfaceChart::SurfacePoint at = panel.chart->surface_point(Vec2(static_cast<float>(u), static_cast<float>(v)));
  out.position = at.position;
  out.outward = panel.chart_side * at.normal;
  out.area_ratio = at.area_ratio;
  out.on_surface = at.on_surface;
  return out;
}

namespace {
// Box from a rectangle through the wall: a hair on the room side, the thickness (and a hair) outside.
Cutter through_wall(const Vec3& origin, const Vec3& u, const Vec3& v, float w, float h, const Vec3& outward,
                       float thickness) {
  Cutter box;
  box.origin = origin;
  box.u_axis = u;
  box.v_axis = v;
  box.normal = outward;
  box.width = w;
  box.height = h;
  box.depth_back = 1e-3f;
  box.depth_front = thickness + 1e-3f;
  return box;
}
}  // namespace

bool OpeningDomain::has_thick_walls() const {
  return std::any_of(panels_.begin(), panels_.end(), [](const Panel& p) { return p.thickness > 0.0f; });
}

int OpeningDomain::element_at(int panel_index, const PanelPoint& q) const {
  if (!(q.u >= 0.0f && q.v >= 0.0f)) return -1;
  return cell(panel_index, static_cast<int>(q.v / element_size_), static_cast<int>(q.u / element_size_));
}

int OpeningDomain::cell(int panel_index, int row, int col) const {
  const Panel& panel = panels_[panel_index];
  if (row < 0 || col < 0 || row >= panel.rows || col >= panel.cols) return -1;
  return panel.grid[static_cast<size_t>(row) * panel.cols + col];
}

namespace {
std::pair<int, int> overlapping(const std::vector<float>& lines, double a, double b, double tolerance) {
  // First cell whose upper line lies above a, last cell whose lower line lies below b.
  const int first = static_cast<int>(std::upper_bound(lines.begin(), lines.end(), a + tolerance) - lines.begin()) - 1;
  const int last = static_cast<int>(std::lower_bound(lines.begin(), lines.end(), b - tolerance) - lines.begin()) - 1;
  const int cells = static_cast<int>(lines.size()) - 1;
  return {a + tolerance < lines.front() ? -1 : first, b - tolerance > lines.back() ? cells : last};
}
}  // namespace

std::pair<int, int> OpeningDomain::columns_overlapping(int panel, double a, double b) const {
  return overlapping(panels_[panel].u_lines, a, b, 1e-6 * element_size_);
}

std::pair<int, int> OpeningDomain::rows_overlapping(int panel, double a, double b) const {
  return overlapping(panels_[panel].v_lines, a, b, 1e-6 * element_size_);
}

int OpeningDomain::lines_ahead(int panel_index, const Vec3& p, const Vec3& dir) const {
  const Panel& panel = panels_[panel_index];
  const Vec3 d = p - panel.origin;
  const float depth = d.dot(panel.outward), along = dir.dot(panel.outward);
  constexpr float kFarthest = 1e3f;  // meters: a line almost parallel to the wall leaves its grid
  float t = kFarthest;
  if (along > 1e-6f) t = std::max(0.0f, panel.thickness - depth) / along;
  if (along < -1e-6f) t = std::max(0.0f, depth) / -along;
  t = std::min(t, kFarthest);
  auto between = [&](const std::vector<float>& lines, float from, float step) {
    const float to = from + t * step, nudge = 1e-5f * element_size_;  // past the line p lies on
    const float lo = std::min(from, to) + (step > 0 ? nudge : 0.0f), hi = std::max(from, to) - (step < 0 ? nudge : 0.0f);
    if (!(hi > lo)) return 0;
    return static_cast<int>(std::lower_bound(lines.begin(), lines.end(), hi) -
                            std::upper_bound(lines.begin(), lines.end(), lo));
  };
  return between(panel.u_lines, d.dot(panel.u_axis), dir.dot(panel.u_axis)) +
         between(panel.v_lines, d.dot(panel.v_axis), dir.dot(panel.v_axis));
}

bool OpeningDomain::on_line(const std::vector<float>& lines, double x) const {
  const double tolerance = 1e-6 * element_size_ + 1e-6 * std::abs(x);  // lines are floats
  const auto it = std::lower_bound(lines.begin(), lines.end(), static_cast<float>(x - tolerance));
  return it != lines.end() && std::abs(*it - x) <= tolerance;
}

Cutter OpeningDomain::element_cutter(int element) const {
  const Element& e = elements_[element];
  const Panel& panel = panels_[e.panel];
  if (panel.curved()) return panel_rectangle_cutter(e.panel, e.u0, e.u1, e.v0, e.v1);
  return through_wall(e.corners[0], panel.u_axis, panel.v_axis, e.width(), e.height(), panel.outward,
                      panel.thickness);
}

Cutter OpeningDomain::panel_rectangle_cutter(int panel_index, double u0, double u1, double v0, double v1) const {
  const Panel& panel = panels_[panel_index];
  if (!panel.curved()) {
    const Vec3 corner = panel.origin + static_cast<float>(u0) * panel.u_axis + static_cast<float>(v0) * panel.v_axis;
    return through_wall(corner, panel.u_axis, panel.v_axis, static_cast<float>(u1 - u0), static_cast<float>(v1 - v0),
                        panel.outward, panel.thickness);
  }
  Cutter c;
  c.chart = panel.chart.get();
  c.u0 = static_cast<float>(u0), c.u1 = static_cast<float>(u1);
  c.v0 = static_cast<float>(v0), c.v1 = static_cast<float>(v1);
  c.normal = panel.outward;
  return c;
}

Cutter OpeningDomain::rectangle_cutter(const std::array<Vec3, 4>& c, int* panel_out) const {
  for (const auto& p : c)
    if (!is_finite(p)) throw std::invalid_argument("has a non-finite corner");
  const Vec3 e1 = c[1] - c[0], e2 = c[3] - c[0];
  const float w = e1.norm(), h = e2.norm();
  if (!(w > 1e-4f && h > 1e-4f)) throw std::invalid_argument("is degenerate (an edge shorter than 0.1 mm)");
  if (std::abs(e1.dot(e2)) > 1e-3f * w * h || (c[2] - (c[1] + e2)).norm() > 1e-3f)
    throw std::invalid_argument("is not a rectangle (corners must be given in order around it)");
  const Vec3 center = 0.25f * (c[0] + c[1] + c[2] + c[3]);
  const Vec3 n = e1.cross(e2).normalized();
  for (size_t i = 0; i < panels_.size(); ++i) {
    const Panel& panel = panels_[i];
    if (panel.curved() || std::abs(n.dot(panel.normal)) < 0.999f) continue;
    if (std::abs((center - panel.origin).dot(panel.normal)) > kPlaneTolerance + 1e-3f) continue;
    const Vec3 d = center - panel.origin;
    const float a = d.dot(panel.u_axis), b = d.dot(panel.v_axis);
    const float margin = element_size_;  // the grid may sit inside the panel's edge by up to one element
    if (a < -margin || b < -margin || a > panel.u_lines.back() + margin || b > panel.v_lines.back() + margin)
      continue;
    const Vec3 u = e1 / w;
    Vec3 v = panel.normal.cross(u);
    if (v.dot(e2) < 0.0f) v = -v;
    const Cutter box = through_wall(c[0], u, v, w, std::abs(e2.dot(v)), panel.outward, panel.thickness);
    if (panel_out) *panel_out = static_cast<int>(i);
    return box;
  }
  throw std::invalid_argument("does not lie on any flat opening-domain panel (openings on curved panels are given by "
                              "\"panel\" and \"parameter_rectangle\")");
}

}  // namespace fenestra
