#include "scene/opening_domain.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "cost/load_checks.h"

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

uint64_t position_key(const Vec3& p) {
  auto q = [](float x) { return static_cast<uint64_t>(static_cast<int64_t>(std::llround(x * 1e5)) & 0x1FFFFF); };
  return q(p.x()) | (q(p.y()) << 21) | (q(p.z()) << 42);
}

// Rows run horizontally on walls and tilted roofs; flat roofs take +X as their row direction.
void panel_axes(const Vec3& n, Vec3* u, Vec3* v) {
  if (std::abs(n.z()) < 0.999f) {
    *u = Vec3(0, 0, 1).cross(n).normalized();
  } else {
    *u = (Vec3(1, 0, 0) - n.x() * n).normalized();
  }
  *v = n.cross(*u);
}

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

std::string describe_panel(const Mesh& mesh, const std::vector<std::string>& material_names,
                           const std::vector<uint32_t>& tris) {
  const uint32_t t = tris.front();
  std::string label = "material '" + material_names[mesh.triangle_material[t]] + "'";
  if (mesh.triangle_group[t] >= 0) label += ", group '" + mesh.group_names[mesh.triangle_group[t]] + "'";
  return label;
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

  // Coplanar faces sharing a vertex position form one panel.
  std::vector<Vec3> unit_normal(tris.size());
  for (size_t i = 0; i < tris.size(); ++i) unit_normal[i] = mesh.area_normal(tris[i]).normalized();
  UnionFind uf(tris.size());
  std::unordered_map<uint64_t, std::vector<int>> by_vertex;
  for (size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) by_vertex[position_key(mesh.vertex(tris[i], k))].push_back(static_cast<int>(i));
  for (const auto& entry : by_vertex) {
    const auto& list = entry.second;
    for (size_t a = 0; a < list.size(); ++a)
      for (size_t b = a + 1; b < list.size(); ++b) {
        const int i = list[a], j = list[b];
        if (unit_normal[i].dot(unit_normal[j]) < 1.0f - kNormalTolerance) continue;
        if (std::abs(unit_normal[i].dot(mesh.vertex(tris[j], 0) - mesh.vertex(tris[i], 0))) > kPlaneTolerance) continue;
        uf.unite(i, j);
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
    Vec3 n = Vec3::Zero();
    for (uint32_t t : comp) n += mesh.area_normal(t);
    panel.area = 0.5 * n.norm();
    n.normalize();
    panel.normal = n;
    panel.outward = n;
    panel_axes(n, &panel.u_axis, &panel.v_axis);

    const Vec3 o = mesh.vertex(comp.front(), 0);
    std::vector<Triangle2D> flat;
    float amin = 1e30f, amax = -1e30f, bmin = 1e30f, bmax = -1e30f;
    for (uint32_t t : comp) {
      Vec2 q[3];
      for (int k = 0; k < 3; ++k) {
        const Vec3 d = mesh.vertex(t, k) - o;
        q[k] = Vec2(d.dot(panel.u_axis), d.dot(panel.v_axis));
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
    panel.origin = o + a0 * panel.u_axis + b0 * panel.v_axis;

    const int panel_index = static_cast<int>(domain.panels_.size());
    panel.grid.assign(static_cast<size_t>(panel.rows) * panel.cols, -1);
    auto inside = [&](const Vec2& p) {
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
        const Vec3 c0 = panel.origin + (c * s) * panel.u_axis + (r * s) * panel.v_axis;
        e.corners = {c0, c0 + s * panel.u_axis, c0 + s * (panel.u_axis + panel.v_axis), c0 + s * panel.v_axis};
        e.center = c0 + 0.5f * s * (panel.u_axis + panel.v_axis);
        panel.grid[static_cast<size_t>(r) * panel.cols + c] = static_cast<int>(domain.elements_.size());
        domain.elements_.push_back(e);
      }
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
  for (Panel& panel : panels_) {
    double side = 0.0;
    for (const Vec3& p : sensor_points) side += (p - panel.origin).dot(panel.normal) > 0.0f ? 1.0 : -1.0;
    panel.outward = side > 0.0 ? Vec3(-panel.normal) : panel.normal;
  }
}

namespace {
// Box from a rectangle through the wall: a hair on the room side, the thickness (and a hair) outside.
CutterBox through_wall(const Vec3& origin, const Vec3& u, const Vec3& v, float w, float h, const Vec3& outward,
                       float thickness) {
  CutterBox box;
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

int OpeningDomain::element_at(int panel_index, const Vec3& p) const {
  const Panel& panel = panels_[panel_index];
  const Vec3 d = p - panel.origin;
  const float a = d.dot(panel.u_axis) / element_size_;
  const float b = d.dot(panel.v_axis) / element_size_;
  if (!(a >= 0.0f && b >= 0.0f)) return -1;
  const int c = static_cast<int>(a), r = static_cast<int>(b);
  if (c >= panel.cols || r >= panel.rows) return -1;
  return panel.grid[static_cast<size_t>(r) * panel.cols + c];
}

CutterBox OpeningDomain::element_cutter(int element) const {
  const Element& e = elements_[element];
  const Panel& panel = panels_[e.panel];
  return through_wall(e.corners[0], panel.u_axis, panel.v_axis, element_size_, element_size_, panel.outward,
                      panel.thickness);
}

CutterBox OpeningDomain::rectangle_cutter(const std::array<Vec3, 4>& c, int* panel_out) const {
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
    if (std::abs(n.dot(panel.normal)) < 0.999f) continue;
    if (std::abs((center - panel.origin).dot(panel.normal)) > kPlaneTolerance + 1e-3f) continue;
    const Vec3 d = center - panel.origin;
    const float a = d.dot(panel.u_axis), b = d.dot(panel.v_axis);
    const float margin = element_size_;  // the grid may sit inside the panel's edge by up to one element
    if (a < -margin || b < -margin || a > (panel.cols + 1) * element_size_ || b > (panel.rows + 1) * element_size_)
      continue;
    const Vec3 u = e1 / w;
    Vec3 v = panel.normal.cross(u);
    if (v.dot(e2) < 0.0f) v = -v;
    const CutterBox box = through_wall(c[0], u, v, w, std::abs(e2.dot(v)), panel.outward, panel.thickness);
    if (panel_out) *panel_out = static_cast<int>(i);
    return box;
  }
  throw std::invalid_argument("does not lie on any opening-domain panel");
}

}  // namespace fenestra
