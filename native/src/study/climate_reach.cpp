#include "study/climate_reach.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "scene/scene.h"
#include "trace/ray_scene.h"

namespace fenestra {
namespace {

// Whether the segment from `from` to the element's centre crosses nothing but the domain (the
// elements are open in the records: paths cross them).
bool sees(const RayScene& rays, const std::vector<uint8_t>& domain_triangle, const Vec3& from, const Vec3& to) {
  Vec3 dir = to - from;
  const float length = dir.norm();
  if (!(length > 0.0f)) return true;
  dir /= length;
  const float end = length * (1.0f - 1e-4f);
  float t = 0.0f;
  for (int crossings = 0; crossings < 64; ++crossings) {
    const Hit hit = rays.intersect(from, dir, t, end, nullptr);
    if (!hit.valid()) return true;
    if (hit.geometry != RayScene::kSceneGeometry || !domain_triangle[hit.primitive]) return false;
    t = hit.t * (1.0f + 1e-5f) + 1e-5f;
  }
  return false;
}

}  // namespace

std::vector<double> climate_reach(const Scene& scene) {
  std::vector<double> out(scene.sensors.size(), 0.0);
  std::vector<uint8_t> goal(scene.sensors.size(), 0);
  for (const ClimateGoal& g : scene.sensors.climate_goals.goals)
    for (int i : g.sensors) goal[i] = 1;
  const std::vector<Element>& elements = scene.domain.elements();
  if (elements.empty() || std::find(goal.begin(), goal.end(), 1) == goal.end()) return out;
  std::vector<uint8_t> domain_triangle(scene.mesh.triangle_count(), 0);
  for (const Panel& p : scene.domain.panels())
    for (uint32_t t : p.triangles) domain_triangle[t] = 1;
  const RayScene rays(scene.mesh, Mesh());
  const double all = static_cast<double>(elements.size());
  tbb::parallel_for(size_t(0), scene.sensors.size(), [&](size_t s) {
    if (!goal[s]) return;
    double seen = 0.0;
    for (const Element& e : elements) seen += sees(rays, domain_triangle, scene.sensors.points[s], e.center);
    out[s] = std::min(all, std::ceil(kClimateReachMargin * seen));
  });
  return out;
}

}  // namespace fenestra
