#include "trace/scene_hits.h"

#include <cmath>
#include <limits>

#include "scene/bsdf.h"

namespace fenestra {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

std::vector<Vec3> unit_normals(const Mesh& mesh) {
  std::vector<Vec3> n(mesh.triangle_count());
  for (size_t t = 0; t < n.size(); ++t) n[t] = mesh.area_normal(t).normalized();
  return n;
}

}  // namespace

SceneHits::SceneHits(const Scene& scene, Mesh reveals) : scene_(scene), reveals_(std::move(reveals)) {
  scene_normals_ = unit_normals(scene_.mesh);
  reveal_normals_ = unit_normals(reveals_);
  const Mesh reveal_grid = scene_.domain.reveal_grid(&reveal_grid_faces_);
  rays_ = std::make_unique<RayScene>(scene_.mesh, reveals_, reveal_grid);
}

Surface SceneHits::surface(const Hit& hit) const {
  Surface s;
  if (hit.geometry == RayScene::kRevealGeometry) {
    s.normal = reveal_normals_[hit.primitive];
    s.material = reveals_.triangle_material[hit.primitive];
  } else if (hit.geometry == RayScene::kRevealGridGeometry) {
    s.reveal_grid_face = static_cast<int>(hit.primitive / 2);  // two triangles per face
    const RevealGridFace& f = reveal_grid_faces_[s.reveal_grid_face];
    s.normal = f.normal;
    s.material = scene_.domain.panels()[f.panel].material;
  } else {
    s.normal = scene_normals_[hit.primitive];
    s.material = scene_.mesh.triangle_material[hit.primitive];
    s.triangle = hit.primitive;
    s.panel = scene_.domain.panel_of_triangle(hit.primitive);
    if (s.panel < 0) {
      s.panel = scene_.domain.outer_panel_of_triangle(hit.primitive);
      s.outer = s.panel >= 0;
    }
  }
  return s;
}

Crossing SceneHits::crossing_met(const Surface& s, const Vec3& p, const Vec3& dir) const {
  if (s.reveal_grid_face >= 0) {  // the cell the ray would go on into
    const RevealGridFace& f = reveal_grid_faces_[s.reveal_grid_face];
    const int k = dir.dot(f.normal) > 0.0f ? f.upper : f.lower;
    // The hit lies on the grid line between two cells, where "inside an opening" is a matter of
    // rounding: the cell's centre stands for it (tubes follow the grid).
    if (k < 0) return {};
    return {k, scene_.domain.panel_point(f.panel, scene_.domain.elements()[k].center)};
  }
  if (s.panel < 0) return {};
  const PanelPoint at = scene_.domain.panel_point(s.panel, s.triangle, p);
  return {scene_.domain.element_at(s.panel, at), at};
}

void SceneHits::shadow(const Vec3& org, const Vec3& dir, const CutterSet* cutters, bool collect, Shadow* out) const {
  out->visible = false;
  out->truncated = false;
  out->attenuation = Rgb::Ones();
  out->crossed_count = 0;
  out->first_is_element = false;
  // Elements crossed so far are cut too, through the wall thickness (the set is built on the
  // first crossing: most shadow rays cross none).
  CutterSet with_crossed;
  const CutterSet* active = cutters;
  float tnear = 0.0f;
  for (int i = 0; i < 64; ++i) {
    const Hit h = rays_->intersect(org, dir, tnear, kInfinity, active);
    if (!h.valid()) {
      out->visible = true;
      return;
    }
    const Surface s = surface(h);
    tnear = h.t + kRayEpsilon;
    if (collect && (s.panel >= 0 || s.reveal_grid_face >= 0)) {
      const Crossing crossing = crossing_met(s, org + h.t * dir, dir);
      const int k = crossing.element;
      if (k < 0) return;  // the panel's margin is always wall
      if (out->crossed_count == kMaxCrossed) {
        out->truncated = true;
        return;
      }
      if (i == 0 && s.inner_face()) out->first_is_element = true;
      out->crossed_distance[out->crossed_count] = h.t;
      out->crossed[out->crossed_count++] = crossing;
      if (active != &with_crossed) {
        if (cutters) with_crossed = *cutters;
        active = &with_crossed;
      }
      with_crossed.push_back(scene_.domain.element_cutter(k));
      continue;
    }
    const Material& m = scene_.materials[s.material];
    if (!m.is_thin_glass()) return;
    out->attenuation *= thin_glass_transmittance(m, std::abs(dir.dot(s.normal)));
  }
}

}  // namespace fenestra
