// The wall behind each opening-domain panel: its thickness (measured from the model's outer face,
// or given), the outer face and edge strips a given thickness adds, and the grid of faces that
// line the elements' tubes through it.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "scene/opening_domain.h"

namespace fenestra {
namespace {

// Parallel faces farther behind a panel than this are other buildings, not its wall's outer face.
constexpr float kMaxMeasuredThickness = 2.0f;  // meters
// Outer faces this close to one offset are one face; a given thickness this close to the measured one agrees.
constexpr float kThicknessTolerance = 2e-3f;  // meters (or 1 % of the thickness, whichever is larger)
constexpr float kParallel = 0.9999f;           // |cos| between a panel's normal and its outer face's
// Fractions of a panel's elements whose centres must have an outer face behind them: at least
// kModelled makes the panel a modelled solid; between kIgnored and kModelled the model is ambiguous.
constexpr double kModelled = 0.5, kIgnored = 0.25;
constexpr size_t kMaxSamples = 4096;  // element centres probed per panel

float tolerance(float thickness) { return std::max(kThicknessTolerance, 0.01f * thickness); }

struct Flat {
  Vec2 a, b, c;
  float lo_u, hi_u, lo_v, hi_v;
  bool contains(const Vec2& p) const {
    if (p.x() < lo_u || p.x() > hi_u || p.y() < lo_v || p.y() > hi_v) return false;
    auto edge = [](const Vec2& p0, const Vec2& p1, const Vec2& q) {
      return (p1.x() - p0.x()) * (q.y() - p0.y()) - (p1.y() - p0.y()) * (q.x() - p0.x());
    };
    const float e0 = edge(a, b, p), e1 = edge(b, c, p), e2 = edge(c, a, p);
    return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
  }
};

// A scene triangle parallel to a panel, behind it: where it lies in the panel's (u, v) frame.
struct Candidate {
  uint32_t triangle;
  float offset;  // meters along the panel's outward direction
  Flat flat;
};

// The scene's triangles outside the domain, bucketed by their unit normal (sign chosen so that
// opposite normals share a bucket): faces parallel to a panel are found in the buckets around its
// normal instead of a scan of the whole mesh per panel.
class NormalIndex {
 public:
  NormalIndex(const Mesh& mesh, const std::vector<int>& triangle_panel, float cell) : cell_(cell) {
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
      if (t < triangle_panel.size() && triangle_panel[t] >= 0) continue;
      const Vec3 n = mesh.area_normal(t);
      if (!(n.norm() > 0.0f)) continue;
      buckets_[key(canonical(n.normalized()), 0, 0, 0)].push_back(static_cast<uint32_t>(t));
    }
  }
  // Every triangle whose normal is within one cell of n or of -n (a superset of the parallel ones).
  template <typename F>
  void near(const Vec3& n, F visit) const {
    for (const Vec3& m : {canonical(n), Vec3(-canonical(n))})
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            const auto it = buckets_.find(key(m, dx, dy, dz));
            if (it == buckets_.end()) continue;
            for (uint32_t t : it->second) visit(t);
          }
  }

 private:
  static Vec3 canonical(const Vec3& n) {
    const bool flip = n.x() < 0.0f || (n.x() == 0.0f && (n.y() < 0.0f || (n.y() == 0.0f && n.z() < 0.0f)));
    return flip ? Vec3(-n) : n;
  }
  uint64_t key(const Vec3& n, int dx, int dy, int dz) const {
    auto q = [&](float v, int d) { return static_cast<uint64_t>(std::floor(v / cell_) + d + 4096) & 0x1FFFFF; };
    return q(n.x(), dx) | (q(n.y(), dy) << 21) | (q(n.z(), dz) << 42);
  }
  float cell_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> buckets_;
};

std::vector<Candidate> parallel_faces_behind(const Mesh& mesh, const Panel& panel, const NormalIndex& index,
                                             float grid_w, float grid_h) {
  std::vector<Candidate> out;
  index.near(panel.normal, [&](uint32_t t) {
    const Vec3 n = mesh.area_normal(t);
    const float len = n.norm();
    if (!(len > 0.0f) || std::abs(n.dot(panel.normal)) < kParallel * len) return;
    const float offset = (mesh.vertex(t, 0) - panel.origin).dot(panel.outward);
    if (!(offset > 1e-3f && offset <= kMaxMeasuredThickness)) return;
    Candidate c{t, offset, {}};
    Vec2 q[3];
    for (int k = 0; k < 3; ++k) {
      const Vec3 d = mesh.vertex(t, k) - panel.origin;
      q[k] = Vec2(d.dot(panel.u_axis), d.dot(panel.v_axis));
    }
    c.flat = {q[0], q[1], q[2], std::min({q[0].x(), q[1].x(), q[2].x()}), std::max({q[0].x(), q[1].x(), q[2].x()}),
              std::min({q[0].y(), q[1].y(), q[2].y()}), std::max({q[0].y(), q[1].y(), q[2].y()})};
    if (c.flat.hi_u < 0.0f || c.flat.lo_u > grid_w || c.flat.hi_v < 0.0f || c.flat.lo_v > grid_h) return;
    out.push_back(c);
  });
  return out;
}

struct Measured {
  double coverage = 0.0;      // fraction of probed element centres with an outer face behind
  float thickness = 0.0f;     // median offset of those faces
  float spread = 0.0f;        // max - min offset
};

Measured measure(const Panel& panel, const std::vector<Element>& elements, const std::vector<Candidate>& faces) {
  Measured m;
  std::vector<int> cells;
  for (int e : panel.grid)
    if (e >= 0) cells.push_back(e);
  const size_t stride = std::max<size_t>(1, cells.size() / kMaxSamples);
  std::vector<float> offsets;
  size_t probed = 0;
  for (size_t i = 0; i < cells.size(); i += stride, ++probed) {
    const Element& e = elements[cells[i]];
    const Vec2 p(0.5f * (e.u0 + e.u1), 0.5f * (e.v0 + e.v1));
    float nearest = std::numeric_limits<float>::infinity();
    for (const Candidate& c : faces)
      if (c.offset < nearest && c.flat.contains(p)) nearest = c.offset;
    if (std::isfinite(nearest)) offsets.push_back(nearest);
  }
  if (probed == 0 || offsets.empty()) return m;
  std::sort(offsets.begin(), offsets.end());
  m.coverage = static_cast<double>(offsets.size()) / static_cast<double>(probed);
  m.thickness = offsets[offsets.size() / 2];
  m.spread = offsets.back() - offsets.front();
  return m;
}

std::string meters(float v) {
  std::ostringstream s;
  s << v << " m";
  return s.str();
}

void add_triangle(Mesh* mesh, const Vec3& a, const Vec3& b, const Vec3& c, int material) {
  const uint32_t base = static_cast<uint32_t>(mesh->positions.size());
  mesh->positions.insert(mesh->positions.end(), {a, b, c});
  mesh->triangles.push_back({base, base + 1, base + 2});
  mesh->triangle_material.push_back(material);
  mesh->triangle_group.push_back(-1);
}

void add_quad(Mesh* mesh, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int material) {
  add_triangle(mesh, a, b, c, material);
  add_triangle(mesh, a, c, d, material);
}

// The panel's faces moved to the wall's outer side, and strips closing the wall along the panel's
// outline (edges used by one of its triangles).
void add_wall_body(const Panel& panel, Mesh* mesh) {
  const Vec3 back = panel.thickness * panel.outward;
  std::map<std::pair<uint32_t, uint32_t>, int> edge_use;
  const Mesh& m = *mesh;
  std::vector<std::array<Vec3, 3>> corners;
  for (uint32_t t : panel.triangles) {
    corners.push_back({m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2)});
    for (int k = 0; k < 3; ++k) {
      uint32_t a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      ++edge_use[{a, b}];
    }
  }
  // Edges shared through duplicated vertices (same position, different index) are inner edges too.
  std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> by_position;
  auto key = [](const Vec3& p) { return std::array<float, 3>{p.x(), p.y(), p.z()}; };
  for (const auto& [edge, uses] : edge_use) {
    auto a = key(m.positions[edge.first]), b = key(m.positions[edge.second]);
    if (b < a) std::swap(a, b);
    by_position[{a, b}] += uses;
  }
  for (const auto& c : corners) add_triangle(mesh, c[0] + back, c[2] + back, c[1] + back, panel.material);
  for (const auto& [edge, uses] : by_position) {
    if (uses != 1) continue;
    const Vec3 a(edge.first[0], edge.first[1], edge.first[2]), b(edge.second[0], edge.second[1], edge.second[2]);
    add_quad(mesh, a, b, b + back, a + back, panel.material);
  }
}

// Distance along the ray to triangle t (Moeller-Trumbore), infinity when missed.
float ray_distance(const Mesh& mesh, size_t t, const Vec3& org, const Vec3& dir) {
  const Vec3 a = mesh.vertex(t, 0), e1 = mesh.vertex(t, 1) - a, e2 = mesh.vertex(t, 2) - a;
  const Vec3 p = dir.cross(e2);
  const float det = e1.dot(p);
  if (std::abs(det) < 1e-12f) return std::numeric_limits<float>::infinity();
  const Vec3 s = org - a;
  const float b1 = s.dot(p) / det;
  const Vec3 q = s.cross(e1);
  const float b2 = dir.dot(q) / det;
  const float d = e2.dot(q) / det;
  return b1 >= 0.0f && b2 >= 0.0f && b1 + b2 <= 1.0f && d > 0.0f ? d : std::numeric_limits<float>::infinity();
}

// Fraction of (up to 32 of) a curved panel's elements with another face of the model close behind
// them, facing the same way: a wall modelled as a solid, which curved panels cannot model yet.
double curved_solid_coverage(const Mesh& mesh, const OpeningDomain& domain, int panel_index) {
  const Panel& panel = domain.panels()[panel_index];
  std::vector<int> cells;
  for (int e : panel.grid)
    if (e >= 0) cells.push_back(e);
  const size_t stride = std::max<size_t>(1, cells.size() / 32);
  size_t probed = 0, behind = 0;
  for (size_t i = 0; i < cells.size(); i += stride, ++probed) {
    const Element& e = domain.elements()[cells[i]];
    const DomainSurfacePoint at = domain.surface_at(panel_index, 0.5 * (e.u0 + e.u1), 0.5 * (e.v0 + e.v1));
    const Vec3 org = at.position + 1e-4f * at.outward;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
      if (domain.panel_of_triangle(t) == panel_index) continue;
      const Vec3 n = mesh.area_normal(t);
      if (std::abs(n.dot(at.outward)) < 0.9f * n.norm()) continue;
      if (ray_distance(mesh, t, org, at.outward) <= kMaxMeasuredThickness) {
        ++behind;
        break;
      }
    }
  }
  return probed ? static_cast<double>(behind) / static_cast<double>(probed) : 0.0;
}

}  // namespace

void OpeningDomain::check_curved_walls(const Mesh& mesh) const {
  for (size_t p = 0; p < panels_.size(); ++p) {
    const Panel& panel = panels_[p];
    if (!panel.curved()) continue;
    if (given_thickness_ && *given_thickness_ > 0.0f)
      throw std::invalid_argument("opening_domain.thickness " + meters(*given_thickness_) +
                                  ": the opening-domain panel of " + panel.label +
                                  " is curved, and curved walls are modelled as single surfaces (thickness 0); "
                                  "give the curved wall its own scene, or leave thickness out");
    if (curved_solid_coverage(mesh, *this, static_cast<int>(p)) >= kModelled)
      throw std::invalid_argument("the curved opening-domain panel of " + panel.label +
                                  " is modelled as a solid (another face lies behind it, facing the same way); "
                                  "curved walls are modelled as single surfaces: mark one surface, and remove the "
                                  "faces behind it");
  }
}

void OpeningDomain::build_walls(Mesh* mesh) {
  check_curved_walls(*mesh);
  outer_panel_.assign(mesh->triangle_count(), -1);
  // Buckets at least as wide as the distance between two unit normals with |n1 . n2| >= kParallel,
  // sqrt(2 (1 - kParallel)); of the model as read (added wall bodies are no one's outer faces).
  const NormalIndex index(*mesh, triangle_panel_, std::sqrt(2.0f * (1.0f - kParallel)) + 1e-3f);
  for (size_t p = 0; p < panels_.size(); ++p) {
    Panel& panel = panels_[p];
    if (panel.curved()) continue;  // a single surface (check_curved_walls)
    const std::vector<Candidate> faces =
        parallel_faces_behind(*mesh, panel, index, panel.u_lines.back(), panel.v_lines.back());
    const Measured m = measure(panel, elements_, faces);
    if (m.coverage >= kIgnored && m.coverage < kModelled) {
      std::ostringstream msg;
      msg << "the wall behind the opening-domain panel of " << panel.label << " is modelled in part only: "
          << std::lround(100.0 * m.coverage) << " % of its elements have its outer face "
          << meters(m.thickness) << " behind them; model the whole wall as a solid, or none of it";
      throw std::invalid_argument(msg.str());
    }
    panel.solid_modelled = m.coverage >= kModelled;
    if (panel.solid_modelled && m.spread > tolerance(m.thickness)) {
      std::ostringstream msg;
      msg << "the wall behind the opening-domain panel of " << panel.label << " is not of one thickness: its outer "
          << "faces lie " << meters(m.thickness - m.spread) << " to " << meters(m.thickness) << " or more behind it; "
          << "mark each part of a different thickness as its own panel";
      throw std::invalid_argument(msg.str());
    }
    if (panel.solid_modelled && given_thickness_ && std::abs(*given_thickness_ - m.thickness) > tolerance(m.thickness)) {
      std::ostringstream msg;
      msg << "opening_domain.thickness " << meters(*given_thickness_) << " disagrees with the wall modelled behind "
          << "the opening-domain panel of " << panel.label << ": its outer face is " << meters(m.thickness)
          << " behind the marked face (leave thickness out to use the model's)";
      throw std::invalid_argument(msg.str());
    }
    panel.thickness = panel.solid_modelled ? m.thickness : given_thickness_.value_or(0.0f);
    if (panel.solid_modelled) {
      for (const Candidate& c : faces)
        if (std::abs(c.offset - m.thickness) <= tolerance(m.thickness) && outer_panel_[c.triangle] < 0)
          outer_panel_[c.triangle] = static_cast<int>(p);
    } else if (panel.thickness > 0.0f) {
      const size_t first = mesh->triangle_count();
      add_wall_body(panel, mesh);
      outer_panel_.resize(mesh->triangle_count(), -1);
      for (size_t t = first; t < first + panel.triangles.size(); ++t) outer_panel_[t] = static_cast<int>(p);
    }
  }
}

Mesh OpeningDomain::reveal_grid(std::vector<RevealGridFace>* faces) const {
  Mesh mesh;
  faces->clear();
  for (size_t p = 0; p < panels_.size(); ++p) {
    const Panel& panel = panels_[p];
    if (!(panel.thickness > 0.0f)) continue;
    const Vec3 back = panel.thickness * panel.outward;
    auto cell = [&](int r, int c) {
      return r < 0 || c < 0 || r >= panel.rows || c >= panel.cols ? -1 : panel.grid[static_cast<size_t>(r) * panel.cols + c];
    };
    auto corner = [&](int r, int c) { return panel.origin + panel.u_lines[c] * panel.u_axis + panel.v_lines[r] * panel.v_axis; };
    auto add = [&](int lower, int upper, const Vec3& normal, const Vec3& a, const Vec3& b) {
      if (lower < 0 && upper < 0) return;
      add_quad(&mesh, a, b, b + back, a + back, panel.material);
      faces->push_back({static_cast<int>(p), lower, upper, normal});
    };
    for (int r = 0; r < panel.rows; ++r)
      for (int c = 0; c <= panel.cols; ++c) add(cell(r, c - 1), cell(r, c), panel.u_axis, corner(r, c), corner(r + 1, c));
    for (int r = 0; r <= panel.rows; ++r)
      for (int c = 0; c < panel.cols; ++c) add(cell(r - 1, c), cell(r, c), panel.v_axis, corner(r, c), corner(r, c + 1));
  }
  return mesh;
}

}  // namespace fenestra
