#pragma once
// What a ray meets in the scene the tracer sees: the surface at a hit (its material, the panel of
// the opening domain it belongs to, the side of an element's tube through a thick wall), the
// element a ray crosses there, and shadow rays, which go on through elements and thin glass and
// list the elements they cross.
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "math/vec.h"
#include "scene/scene.h"
#include "trace/ray_scene.h"

namespace fenestra {

constexpr float kRayEpsilon = 1e-4f;  // meters: offset of new rays from the surface they leave
// Elements a shadow ray may cross; one that crosses more is taken as blocked (a truncation).
constexpr int kMaxCrossed = 32;

// The origin of a ray leaving point p (geometric normal ng) along dir, off the surface.
inline Vec3 offset_origin(const Vec3& p, const Vec3& ng, const Vec3& dir) {
  return p + (dir.dot(ng) > 0.0f ? kRayEpsilon : -kRayEpsilon) * ng;
}

// An element met by a ray, and where on its panel.
struct Crossing {
  int32_t element = -1;
  PanelPoint point;
};

struct Surface {
  Vec3 normal;  // unit geometric normal as modelled
  int material = 0;
  int panel = -1;      // opening-domain panel whose inner (domain) or outer face this is
  bool outer = false;  // the outer face of the panel's wall
  int reveal_grid_face = -1;  // a side of an element's tube through a thick wall (RevealGridFace)
  uint32_t triangle = 0;      // the scene triangle, on the scene's geometry
  bool inner_face() const { return panel >= 0 && !outer; }
};

// A surface interaction: position, normals, shading frame, outgoing direction, material.
struct Vertex {
  Vec3 p;
  Vec3 ng;     // geometric normal as modelled
  Vec3 n;      // shading normal, on the side of wo
  Frame frame;  // around n
  Vec3 wo;     // toward where the path came from, in `frame`
  const Material* material = nullptr;
};

struct Shadow {
  bool visible = false;
  bool truncated = false;  // blocked only because it crossed more than kMaxCrossed elements
  Rgb attenuation = Rgb::Ones();
  std::array<Crossing, kMaxCrossed> crossed;
  std::array<float, kMaxCrossed> crossed_distance;
  int crossed_count = 0;
  bool first_is_element = false;  // the ray met an element before anything else (portals reach it)
};

class SceneHits {
 public:
  // `reveals` line the cut openings through the wall (materials per face).
  SceneHits(const Scene& scene, Mesh reveals);

  Hit intersect(const Vec3& org, const Vec3& dir, float tnear, const CutterSet* cutters) const {
    return rays_->intersect(org, dir, tnear, std::numeric_limits<float>::infinity(), cutters);
  }
  Surface surface(const Hit& hit) const;
  // The element a ray along dir meets at surface s (point p), or -1 (no element: the panel's margin).
  Crossing crossing_met(const Surface& s, const Vec3& p, const Vec3& dir) const;
  // A shadow ray: visible when nothing opaque is in the way (`cutters` cut); with `collect`, the
  // elements it meets are listed and gone through (each cut in turn).
  void shadow(const Vec3& org, const Vec3& dir, const CutterSet* cutters, bool collect, Shadow* out) const;

 private:
  const Scene& scene_;
  Mesh reveals_;
  std::vector<Vec3> scene_normals_, reveal_normals_;
  std::vector<RevealGridFace> reveal_grid_faces_;
  std::unique_ptr<RayScene> rays_;
};

}  // namespace fenestra
