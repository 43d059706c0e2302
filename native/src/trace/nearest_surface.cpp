#include "trace/nearest_surface.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "trace/ray_scene.h"

namespace fenestra {
namespace {

struct Query {
  const Mesh* mesh;
  const NearestSurface::Filter* counts;
  NearestHit best;
};

// Called by Embree for each triangle whose bounds meet the query sphere; shrinking the radius
// prunes the rest of the traversal.
bool visit(RTCPointQueryFunctionArguments* args) {
  auto* q = static_cast<Query*>(args->userPtr);
  const unsigned t = args->primID;
  const Vec3 p(args->query->x, args->query->y, args->query->z);
  const Mesh& m = *q->mesh;
  const Vec3 closest = closest_point_on_triangle(p, m.vertex(t, 0), m.vertex(t, 1), m.vertex(t, 2));
  const float d = (closest - p).norm();
  if (!(d < args->query->radius)) return false;
  if (*q->counts && !(*q->counts)(t, closest)) return false;
  args->query->radius = d;
  q->best.distance = d;
  q->best.triangle = static_cast<int>(t);
  return true;
}

}  // namespace

Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return a;
  const Vec3 bp = p - b;
  const float d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0f && d4 <= d3) return b;
  const Vec3 cp = p - c;
  const float d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0f && d5 <= d6) return c;
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return a + (d1 / (d1 - d3)) * ab;
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return a + (d2 / (d2 - d6)) * ac;
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const float denom = va + vb + vc;
  if (!(denom > 0.0f)) return a;  // a degenerate triangle: its first corner stands for it
  return a + (vb / denom) * ab + (vc / denom) * ac;
}

NearestHit nearest_in_view(const NearestSurface& surfaces, const Mesh& mesh, const Vec3& p, const Vec3& n, float radius,
                           const std::vector<uint8_t>* only) {
  constexpr float kParallel = 0.9f;
  const float behind = 1e-4f + 4.0f * std::numeric_limits<float>::epsilon() * p.cwiseAbs().maxCoeff();
  return surfaces.nearest(p, radius, [&](uint32_t t, const Vec3& closest) {
    if (only && !(*only)[t]) return false;
    const Vec3 face = mesh.area_normal(t).normalized();
    return !(std::abs(face.dot(n)) >= kParallel && (closest - p).dot(n) <= behind);
  });
}

NearestSurface::NearestSurface(const Mesh& mesh) : mesh_(mesh) {
  scene_ = rtcNewScene(embree_device());
  RTCGeometry g = embree_triangles(mesh);
  rtcCommitGeometry(g);
  rtcAttachGeometry(scene_, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(scene_);
  if (rtcGetDeviceError(embree_device()) != RTC_ERROR_NONE)
    throw std::runtime_error("Embree failed to build the scene for nearest-surface queries");
}

NearestSurface::~NearestSurface() {
  if (scene_) rtcReleaseScene(scene_);
}

NearestHit NearestSurface::nearest(const Vec3& p, float radius, const Filter& counts) const {
  Query q{&mesh_, &counts, NearestHit{radius, -1}};
  RTCPointQuery query;
  query.x = p.x(), query.y = p.y(), query.z = p.z();
  query.radius = radius;
  query.time = 0.0f;
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(scene_, &query, &context, visit, &q);
  return q.best;
}

}  // namespace fenestra
