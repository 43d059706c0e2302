#pragma once
// A curved panel laid flat: each of its triangles placed in a 2-D chart whose coordinates are
// meters along the surface, from the model's UV map (scaled so that chart and surface have the
// same area) or, without one, by unrolling a developable surface (cylinder, cone, barrel vault)
// across its edges, which keeps lengths exactly. Elements are squares of the chart; a point of the
// surface and its chart point map to each other through the triangle that holds them.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "math/vec.h"
#include "scene/mesh.h"
#include "scene/site_frame.h"

namespace fenestra {

class SurfaceChart {
 public:
  enum class Source { kUvMap, kUnrolled };

  // The chart of `triangles` (one connected, smooth piece of `mesh`): from their UVs when all have
  // them, else unrolled. Throws std::invalid_argument naming `label` and a face position when the
  // UV map is degenerate, folds or overlaps, or when a surface without UVs cannot be unrolled; the
  // position is in the input's coordinates (`site`: where the mesh's local frame sits).
  static SurfaceChart build(const Mesh& mesh, const std::vector<uint32_t>& triangles, const std::string& label,
                            const SiteFrame& site = {});

  Source source() const { return source_; }
  const char* source_name() const { return source_ == Source::kUvMap ? "uv_map" : "unrolled"; }
  size_t triangle_count() const { return flat_.size(); }
  // Chart corners of the i-th triangle (in the order given to build).
  const std::array<Vec2, 3>& flat(size_t i) const { return flat_[i]; }
  // Moves the chart's coordinates by `offset` (the panel places its grid corner at the origin).
  void translate(const Vec2& offset);

  bool holds(uint32_t scene_triangle) const {
    return scene_triangle < local_.size() && local_[scene_triangle] >= 0;
  }
  // Chart point of p, a point of the scene triangle (which the chart must hold).
  Vec2 chart_point(uint32_t scene_triangle, const Vec3& p) const {
    const Affine& m = to_chart_[local_[scene_triangle]];
    const Vec3 d = p - m.origin;
    return m.flat_origin + Vec2(m.row_u.dot(d), m.row_v.dot(d));
  }
  // Surface area per chart area on the triangle (1 when unrolled).
  float area_ratio(uint32_t scene_triangle) const { return area_ratio_[local_[scene_triangle]]; }
  // Unit normal of the scene triangle, on the side for which the chart runs counter-clockwise.
  const Vec3& chart_normal(uint32_t scene_triangle) const { return normal_[local_[scene_triangle]]; }

  struct SurfacePoint {
    Vec3 position, normal;  // normal: chart_normal of the triangle holding it
    float area_ratio = 1.0f;
    bool on_surface = false;  // false: extended from the nearest triangle (the point is off the chart)
  };
  // The surface point of chart point q.
  SurfacePoint surface_point(const Vec2& q) const;
  bool contains(const Vec2& q) const { return locate(q) >= 0; }
  // Chart bounding box.
  Vec2 lower() const { return lower_; }
  Vec2 upper() const { return upper_; }

 private:
  struct Affine {  // chart point = flat_origin + (row_u . (p - origin), row_v . (p - origin))
    Vec3 origin, row_u, row_v;
    Vec2 flat_origin;
  };
  void finish(const Mesh& mesh, const std::vector<uint32_t>& triangles, const std::string& label);
  void build_lookup();
  int locate(const Vec2& q) const;  // local triangle holding q, or -1

  Source source_ = Source::kUnrolled;
  SiteFrame site_;  // for the positions in messages
  std::vector<std::array<Vec3, 3>> corners_;  // surface corners of each local triangle
  std::vector<std::array<Vec2, 3>> flat_;
  std::vector<Vec3> normal_;
  std::vector<float> area_ratio_;
  std::vector<Affine> to_chart_;
  std::vector<int32_t> local_;  // scene triangle -> local index, -1 elsewhere
  Vec2 lower_ = Vec2::Zero(), upper_ = Vec2::Zero();
  // Uniform bins over the bounding box, each listing the triangles whose box overlaps it.
  int bins_u_ = 1, bins_v_ = 1;
  std::vector<std::vector<int>> bins_;
};

}  // namespace fenestra
