#include "study/sensor_grid.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "scene/mesh.h"
#include "trace/nearest_surface.h"
#include "trace/ray_scene.h"
#include "util/number_text.h"

namespace fenestra {
namespace {

constexpr float kFloorSlope = 0.7f;     // |normal z| of a face within about 45 degrees of horizontal
constexpr int kMaxColumnHits = 256;     // faces a column ray passes through, at most
constexpr float kColumnStep = 1e-4f;    // m: a column ray resumes this far past each face
constexpr int kInsetRays = 32;          // horizontal directions a sensor's distance to the walls is read in
constexpr double kUnderCeiling = 0.1;   // m: rooms are told apart this far under the lower ceiling
constexpr double kProbePitch = 0.25;    // m: the columns that find the rooms, at most this far apart
constexpr double kMaxProbes = 4e6;      // columns, at most (a coarser pitch on larger models)
constexpr double kLatticeOffset = 0.0618;  // of a pitch: columns off round coordinates
constexpr float kInfinity = std::numeric_limits<float>::infinity();

struct Floor {
  float z = 0.0f;             // the face's height (local meters)
  float top = kInfinity;      // the next face above it, or infinity
  // The faces' normals: the floor's up and the ceiling's down (a room inside a solid), or the
  // floor's down and the ceiling's up (a thin box room with outward normals, or inside a solid).
  bool facing_in = false, facing_out = false;
  bool enclosed() const { return top < kInfinity; }
};

// The model in a local frame (floats keep millimetres only near the origin: site_frame.h).
struct Model {
  Mesh mesh;
  SiteFrame frame;
  std::vector<uint8_t> candidate;
  float top = 0.0f, bottom = 0.0f;          // z range, with a margin
  double lo_x = 0, lo_y = 0, hi_x = 0, hi_y = 0;  // the candidates' extent in x and y
};

// The probe columns: a regular lattice over the candidates' extent.
struct Probes {
  bool enclosed = false;  // some floor of the chosen objects is under a ceiling
  double x0 = 0, y0 = 0, pitch = 0;
  int nx = 0, ny = 0;
  std::vector<std::vector<Floor>> floors;  // per column, from the top down
  std::vector<int> first_node;             // per column: the index of its first floor among all
  double x(int i) const { return x0 + (i + 0.5) * pitch; }
  double y(int j) const { return y0 + (j + 0.5) * pitch; }
  int at(int i, int j) const { return i * ny + j; }
};

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

float unit_z(const Mesh& mesh, uint32_t t) {
  const Vec3 n = mesh.area_normal(t);
  const float length = n.norm();
  return length > 0.0f ? n.z() / length : 0.0f;
}

Model local_model(const std::vector<Vec3d>& positions, const std::vector<std::array<uint32_t, 3>>& triangles,
                  const std::vector<uint8_t>& candidates) {
  Model m;
  Vec3d lo = Vec3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3d& p : positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  m.frame = SiteFrame::around(lo, hi);
  for (const Vec3d& p : positions) m.mesh.positions.push_back(m.frame.to_local(p));
  m.mesh.triangles = triangles;
  m.candidate = candidates;
  const Vec3 local_lo = m.frame.to_local(lo), local_hi = m.frame.to_local(hi);
  m.top = local_hi.z() + 1.0f, m.bottom = local_lo.z() - 1.0f;
  m.lo_x = m.lo_y = std::numeric_limits<double>::infinity();
  m.hi_x = m.hi_y = -m.lo_x;
  for (size_t t = 0; t < triangles.size(); ++t) {
    if (!candidates[t]) continue;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = m.mesh.vertex(t, k);
      m.lo_x = std::min<double>(m.lo_x, p.x()), m.hi_x = std::max<double>(m.hi_x, p.x());
      m.lo_y = std::min<double>(m.lo_y, p.y()), m.hi_y = std::max<double>(m.hi_y, p.y());
    }
  }
  return m;
}

// The floors of the column at (x, y), each with the face above it.
std::vector<Floor> column_floors(const RayScene& rays, const Model& m, float x, float y) {
  std::vector<Floor> out;
  const Vec3 origin(x, y, m.top), down(0.0f, 0.0f, -1.0f);
  bool above = false;
  float above_z = 0.0f, above_nz = 0.0f, t = 0.0f;
  for (int k = 0; k < kMaxColumnHits; ++k) {
    const Hit hit = rays.intersect(origin, down, t, m.top - m.bottom, nullptr);
    if (!hit.valid()) break;
    const float z = m.top - hit.t, nz = unit_z(m.mesh, hit.primitive);
    if (m.candidate[hit.primitive] && std::abs(nz) >= kFloorSlope) {
      Floor f;
      f.z = z;
      f.top = above ? above_z : kInfinity;
      f.facing_in = nz > 0.0f && above && above_nz < 0.0f;
      f.facing_out = nz < 0.0f && above && above_nz > 0.0f;
      out.push_back(f);
    }
    above = true, above_z = z, above_nz = nz;
    t = hit.t + kColumnStep;
  }
  return out;
}

bool clear_between(const RayScene& rays, const Vec3& a, const Vec3& b) {
  Vec3 d = b - a;
  const float length = d.norm();
  if (!(length > 0.0f)) return true;
  return !rays.intersect(a, d / length, 0.0f, length, nullptr).valid();
}

// Whether floors a and b of neighbouring columns are one room: nothing between their sensors, nor
// just under the lower ceiling (where a door's head parts two rooms).
bool one_room(const RayScene& rays, const Vec3& pa, const Floor& a, const Vec3& pb, const Floor& b, float height) {
  if (std::abs(a.z - b.z) > kFloorStep) return false;
  const Vec3 sa(pa.x(), pa.y(), a.z + height), sb(pb.x(), pb.y(), b.z + height);
  if (!clear_between(rays, sa, sb)) return false;
  if (!a.enclosed() || !b.enclosed()) return true;
  const float under = std::min(a.top, b.top) - static_cast<float>(kUnderCeiling);
  if (!(under > std::max(sa.z(), sb.z()))) return true;
  return clear_between(rays, Vec3(pa.x(), pa.y(), under), Vec3(pb.x(), pb.y(), under));
}

Probes find_floors(const RayScene& rays, const Model& m, const SensorGridSettings& s) {
  Probes p;
  const double width = std::max(m.hi_x - m.lo_x, 1e-3), depth = std::max(m.hi_y - m.lo_y, 1e-3);
  p.pitch = std::min(s.spacing / 2.0, kProbePitch);
  if (width * depth / (p.pitch * p.pitch) > kMaxProbes) p.pitch = std::sqrt(width * depth / kMaxProbes);
  p.nx = std::max(1, static_cast<int>(std::ceil(width / p.pitch))) + 1;
  p.ny = std::max(1, static_cast<int>(std::ceil(depth / p.pitch))) + 1;
  // Off the model's round numbers, so that no column runs along a wall's plane.
  p.x0 = m.lo_x + 0.5 * (width - p.nx * p.pitch) + kLatticeOffset * p.pitch;
  p.y0 = m.lo_y + 0.5 * (depth - p.ny * p.pitch) + kLatticeOffset * p.pitch;
  p.floors.resize(static_cast<size_t>(p.nx) * p.ny);
  const float clear = static_cast<float>(s.height + kGridClearance);
  tbb::parallel_for(0, p.nx, [&](int i) {
    for (int j = 0; j < p.ny; ++j)
      p.floors[p.at(i, j)] = column_floors(rays, m, static_cast<float>(p.x(i)), static_cast<float>(p.y(j)));
  });
  // With any floor under a ceiling, open floors are a roof's top or a terrace: not the rooms meant.
  // Where some room's faces look into it (a room inside a solid), the space between a face looking
  // down and one looking up above it is solid: a thick wall's inside. Else the model's rooms are
  // thin boxes, whose normals may point out of them. Floors with less air above them than the
  // sensors need hold none.
  bool enclosed = false, solid = false;
  for (const auto& column : p.floors)
    for (const Floor& f : column) {
      enclosed = enclosed || f.enclosed();
      solid = solid || (f.facing_in && f.top - f.z >= clear);
    }
  p.enclosed = enclosed;
  for (auto& column : p.floors)
    column.erase(std::remove_if(column.begin(), column.end(),
                                [&](const Floor& f) {
                                  return (enclosed && !f.enclosed()) || (solid && f.facing_out) || f.top - f.z < clear;
                                }),
                 column.end());
  p.first_node.resize(p.floors.size() + 1, 0);
  for (size_t c = 0; c < p.floors.size(); ++c) p.first_node[c + 1] = p.first_node[c] + static_cast<int>(p.floors[c].size());
  return p;
}

// Rooms: the floors' nodes joined across neighbouring columns.
UnionFind join_rooms(const RayScene& rays, const Probes& p, float height) {
  std::vector<std::vector<std::pair<int, int>>> joins(p.floors.size());
  tbb::parallel_for(0, p.nx, [&](int i) {
    for (int j = 0; j < p.ny; ++j) {
      const int c = p.at(i, j);
      const Vec3 pc(static_cast<float>(p.x(i)), static_cast<float>(p.y(j)), 0.0f);
      for (const auto& [di, dj] : {std::pair<int, int>{1, 0}, std::pair<int, int>{0, 1}}) {
        if (i + di >= p.nx || j + dj >= p.ny) continue;
        const int n = p.at(i + di, j + dj);
        const Vec3 pn(static_cast<float>(p.x(i + di)), static_cast<float>(p.y(j + dj)), 0.0f);
        for (size_t a = 0; a < p.floors[c].size(); ++a)
          for (size_t b = 0; b < p.floors[n].size(); ++b)
            if (one_room(rays, pc, p.floors[c][a], pn, p.floors[n][b], height))
              joins[c].emplace_back(p.first_node[c] + static_cast<int>(a), p.first_node[n] + static_cast<int>(b));
      }
    }
  });
  UnionFind rooms(static_cast<size_t>(p.first_node.back()));
  for (const auto& column : joins)
    for (const auto& [a, b] : column) rooms.join(a, b);
  return rooms;
}

struct Box {
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
};

// The upper face of a chosen floor under (x, y) near `near` (furniture between is passed), or NaN.
float floor_under(const RayScene& rays, const Model& m, double x, double y, float near, float height) {
  const Vec3 origin(static_cast<float>(x), static_cast<float>(y), near + height), down(0.0f, 0.0f, -1.0f);
  const float reach = height + static_cast<float>(kFloorStep);
  float t = 0.0f;
  for (int k = 0; k < kMaxColumnHits; ++k) {
    const Hit hit = rays.intersect(origin, down, t, reach, nullptr);
    if (!hit.valid()) break;
    if (m.candidate[hit.primitive] && std::abs(unit_z(m.mesh, hit.primitive)) >= kFloorSlope) return origin.z() - hit.t;
    t = hit.t + kColumnStep;
  }
  return std::numeric_limits<float>::quiet_NaN();
}

// How far the floor at height z reaches from (x, y) along (dx, dy), up to `most` (bisection).
double floor_reach(const RayScene& rays, const Model& m, double x, double y, double dx, double dy, float z,
                   float height, double most) {
  const auto has_floor = [&](double t) {
    return std::abs(floor_under(rays, m, x + t * dx, y + t * dy, z, height) - z) <= kFloorStep;
  };
  if (has_floor(most)) return most;
  double inside = 0.0, outside = most;
  for (int k = 0; k < 24; ++k) {
    const double mid = 0.5 * (inside + outside);
    (has_floor(mid) ? inside : outside) = mid;
  }
  return inside;
}

// A floor of a column: (column, index in the column's floors).
using Member = std::pair<int, int>;

// A room's extent: its columns, reaching out to the walls that bound them.
Box room_extent(const RayScene& rays, const Model& m, const Probes& p, const std::vector<Member>& members, float height) {
  Box box;
  for (const auto& [c, a] : members) {
        const int i = c / p.ny, j = c % p.ny;
        const Floor& f = p.floors[c][a];
        const Vec3 at(static_cast<float>(p.x(i)), static_cast<float>(p.y(j)), f.z + height);
        // To the wall (at the sensors' height, or under the ceiling: a door's head), or else to the
        // floor's edge (a floor without walls).
        const Vec3 under(at.x(), at.y(), f.top - static_cast<float>(kUnderCeiling));
        const auto reach = [&](int di, int dj) {
          const Vec3 dir(static_cast<float>(di), static_cast<float>(dj), 0.0f);
          const float most = static_cast<float>(1.5 * p.pitch);
          float wall = kInfinity;
          for (const Vec3& from : {at, under}) {
            if (!std::isfinite(from.z()) || from.z() < at.z()) continue;
            const Hit hit = rays.intersect(from, dir, 0.0f, most, nullptr);
            if (hit.valid()) wall = std::min(wall, hit.t);
          }
          if (wall < kInfinity) return static_cast<double>(wall);
          return floor_reach(rays, m, p.x(i), p.y(j), di, dj, f.z, height, most);
        };
        box.lo_x = std::min(box.lo_x, p.x(i) - reach(-1, 0));
        box.hi_x = std::max(box.hi_x, p.x(i) + reach(1, 0));
        box.lo_y = std::min(box.lo_y, p.y(j) - reach(0, -1));
        box.hi_y = std::max(box.hi_y, p.y(j) + reach(0, 1));
  }
  return box;
}

// Positions along [lo, hi] at `spacing`, centred, at least `inset` from both ends where they fit.
std::vector<double> lattice(double lo, double hi, double spacing, double inset) {
  const double usable = hi - lo - 2.0 * inset;
  const int n = usable >= 0.0 ? static_cast<int>(std::floor(usable / spacing + 1e-4)) + 1 : 1;
  const double first = lo + 0.5 * (hi - lo - (n - 1) * spacing);
  std::vector<double> out;
  for (int k = 0; k < n; ++k) out.push_back(first + k * spacing);
  return out;
}

// The room's floor at the column nearest (x, y), or none.
const Floor* room_floor(const Probes& p, const std::vector<int>& room_of, int room, double x, double y) {
  const int ci = std::clamp(static_cast<int>(std::floor((x - p.x0) / p.pitch)), 0, p.nx - 1);
  const int cj = std::clamp(static_cast<int>(std::floor((y - p.y0) / p.pitch)), 0, p.ny - 1);
  const Floor* best = nullptr;
  double best_d = std::numeric_limits<double>::infinity();
  for (int i = std::max(0, ci - 1); i <= std::min(p.nx - 1, ci + 1); ++i)
    for (int j = std::max(0, cj - 1); j <= std::min(p.ny - 1, cj + 1); ++j) {
      const int c = p.at(i, j);
      const double d = std::hypot(p.x(i) - x, p.y(j) - y);
      for (size_t a = 0; a < p.floors[c].size(); ++a)
        if (d < best_d && room_of[p.first_node[c] + static_cast<int>(a)] == room) best = &p.floors[c][a], best_d = d;
    }
  return best;
}

bool off_the_walls(const RayScene& rays, const Vec3& at, double inset) {
  const float reach = static_cast<float>(inset * (1.0 - 1e-4));
  if (!(reach > 0.0f)) return true;
  for (int k = 0; k < kInsetRays; ++k) {
    const double a = 2.0 * 3.14159265358979323846 * k / kInsetRays;
    if (rays.intersect(at, Vec3(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f), 0.0f, reach,
                       nullptr)
            .valid())
      return false;
  }
  return true;
}

SensorRoom room_sensors(const RayScene& rays, const NearestSurface& surfaces, const Model& m, const Probes& p,
                        const std::vector<int>& room_of, int room, const std::vector<Member>& members,
                        const SensorGridSettings& s) {
  const float height = static_cast<float>(s.height);
  const Box box = room_extent(rays, m, p, members, height);
  const std::vector<double> xs = lattice(box.lo_x, box.hi_x, s.spacing, s.inset);
  const std::vector<double> ys = lattice(box.lo_y, box.hi_y, s.spacing, s.inset);
  std::vector<float> floor_z(xs.size() * ys.size(), std::numeric_limits<float>::quiet_NaN());
  std::vector<const Floor*> near(floor_z.size());
  for (size_t a = 0; a < xs.size(); ++a)
    for (size_t b = 0; b < ys.size(); ++b) near[a * ys.size() + b] = room_floor(p, room_of, room, xs[a], ys[b]);
  const Vec3 up(0.0f, 0.0f, 1.0f);
  tbb::parallel_for(size_t(0), floor_z.size(), [&](size_t k) {
    if (!near[k]) return;
    const double x = xs[k / ys.size()], y = ys[k % ys.size()];
    const float z = floor_under(rays, m, x, y, near[k]->z, height);
    if (!(std::abs(z - near[k]->z) <= kFloorStep)) return;
    const Vec3 at(static_cast<float>(x), static_cast<float>(y), z + height);
    if (nearest_in_view(surfaces, m.mesh, at, up, static_cast<float>(kGridClearance)).found()) return;
    if (!off_the_walls(rays, at, s.inset)) return;
    floor_z[k] = z;
  });
  SensorRoom sensors;
  std::vector<int> index(floor_z.size(), -1);
  for (size_t k = 0; k < floor_z.size(); ++k) {
    if (std::isnan(floor_z[k])) continue;
    index[k] = static_cast<int>(sensors.points.size());
    const double floor_site = static_cast<double>(floor_z[k]) + m.frame.origin.z();
    sensors.points.emplace_back(xs[k / ys.size()] + m.frame.origin.x(), ys[k % ys.size()] + m.frame.origin.y(),
                             floor_site + s.height);
    sensors.floor_z.push_back(floor_site);
  }
  for (size_t a = 0; a + 1 < xs.size(); ++a)
    for (size_t b = 0; b + 1 < ys.size(); ++b) {
      const size_t k = a * ys.size() + b;
      const std::array<int, 4> q = {index[k], index[k + ys.size()], index[k + ys.size() + 1], index[k + 1]};
      if (std::all_of(q.begin(), q.end(), [](int v) { return v >= 0; })) sensors.quads.push_back(q);
    }
  return sensors;
}

void check_settings(const SensorGridSettings& s, const Model& m) {
  const auto positive = [](double v, const char* name, double most) {
    if (!(std::isfinite(v) && v > 0.0 && v <= most))
      throw std::invalid_argument(std::string("sensor grid: ") + name + " " + decimal_text(v, "%g") +
                                  " m is not a length above 0 m and at most " + decimal_text(most, "%g") + " m");
  };
  positive(s.height, "height", 100.0);
  positive(s.spacing, "spacing", 100.0);
  if (!(std::isfinite(s.inset) && s.inset >= 0.0 && s.inset <= 100.0))
    throw std::invalid_argument("sensor grid: inset " + decimal_text(s.inset, "%g") +
                                " m is not a length from 0 m to 100 m");
  const double area = std::max(m.hi_x - m.lo_x, 0.0) * std::max(m.hi_y - m.lo_y, 0.0);
  const double sensors = area / (s.spacing * s.spacing);
  if (sensors > kMaxGridSensors)
    throw std::invalid_argument("sensor grid: " + decimal_text(area, "%.0f") + " m2 of floor at a spacing of " +
                                decimal_text(s.spacing, "%g") + " m would hold up to " + decimal_text(sensors, "%.0f") +
                                " sensors (at most " + decimal_text(kMaxGridSensors, "%.0f") +
                                "): use a spacing of at least " +
                                decimal_text(std::ceil(100.0 * std::sqrt(area / kMaxGridSensors)) / 100.0, "%.2f") + " m");
}

}  // namespace

double automatic_inset(double spacing) { return std::max(0.5 * spacing, 0.25); }

SensorGrid sensor_grid(const std::vector<Vec3d>& positions, const std::vector<std::array<uint32_t, 3>>& triangles,
                       const std::vector<uint8_t>& floor_candidates, const SensorGridSettings& given) {
  if (floor_candidates.size() != triangles.size())
    throw std::invalid_argument("sensor grid: " + std::to_string(floor_candidates.size()) + " floor marks for " +
                                std::to_string(triangles.size()) + " triangles");
  for (const auto& t : triangles)
    for (uint32_t v : t)
      if (v >= positions.size())
        throw std::invalid_argument("sensor grid: a triangle names vertex " + std::to_string(v) + " of " +
                                    std::to_string(positions.size()));
  for (const Vec3d& p : positions)
    if (!p.allFinite()) throw std::invalid_argument("sensor grid: a vertex is not a finite position");
  SensorGridSettings s = given;
  if (s.inset < 0.0 && std::isfinite(s.spacing) && s.spacing > 0.0) s.inset = automatic_inset(s.spacing);
  SensorGrid grid;
  if (std::find(floor_candidates.begin(), floor_candidates.end(), 1) == floor_candidates.end()) {
    check_settings(s, Model());
    grid.inset = s.inset;
    return grid;
  }
  const Model m = local_model(positions, triangles, floor_candidates);
  check_settings(s, m);
  grid.inset = s.inset;
  const RayScene rays(m.mesh, Mesh());
  const NearestSurface surfaces(m.mesh);
  const Probes probes = find_floors(rays, m, s);
  grid.enclosed = probes.enclosed;
  UnionFind joined = join_rooms(rays, probes, static_cast<float>(s.height));
  std::vector<int> room_of(static_cast<size_t>(probes.first_node.back()));
  std::vector<std::vector<Member>> members;
  for (size_t c = 0; c < probes.floors.size(); ++c)
    for (size_t a = 0; a < probes.floors[c].size(); ++a) {
      const int node = probes.first_node[c] + static_cast<int>(a), root = joined.find(node);
      if (root == node) room_of[node] = static_cast<int>(members.size()), members.emplace_back();
      else room_of[node] = room_of[root];  // roots are the smallest node of their room: seen first
      members[room_of[node]].emplace_back(static_cast<int>(c), static_cast<int>(a));
    }
  for (size_t r = 0; r < members.size(); ++r) {
    SensorRoom room = room_sensors(rays, surfaces, m, probes, room_of, static_cast<int>(r), members[r], s);
    if (!room.points.empty()) grid.rooms.push_back(std::move(room));
  }
  std::stable_sort(grid.rooms.begin(), grid.rooms.end(), [](const SensorRoom& a, const SensorRoom& b) {
    const double za = *std::min_element(a.floor_z.begin(), a.floor_z.end());
    const double zb = *std::min_element(b.floor_z.begin(), b.floor_z.end());
    if (std::abs(za - zb) > kFloorStep) return za < zb;
    if (a.points[0].x() != b.points[0].x()) return a.points[0].x() < b.points[0].x();
    return a.points[0].y() < b.points[0].y();
  });
  return grid;
}

}  // namespace fenestra
