#pragma once
// Embree device and scene as RAII types, with per-ray cutters riding in an extended context.
#include <embree3/rtcore.h>

#include <memory>
#include <vector>

#include "scene/cutter.h"
#include "scene/mesh.h"

namespace fenestra {

// One Embree device per process; errors are turned into exceptions at the call that caused them.
RTCDevice embree_device();

// A new Embree triangle geometry holding `mesh`'s positions and triangles (not yet committed).
RTCGeometry embree_triangles(const Mesh& mesh);

// Rays traced by this thread so far (intersect calls); parallel_tasks adds them to rays_traced().
uint64_t& thread_ray_count();
// Rays traced by all parallel_tasks since the process started.
uint64_t rays_traced();
void add_rays_traced(uint64_t n);

struct Hit {
  float t = 0.0f;
  uint32_t geometry = RTC_INVALID_GEOMETRY_ID;  // kSceneGeometry or kRevealGeometry
  uint32_t primitive = 0;
  bool valid() const { return geometry != RTC_INVALID_GEOMETRY_ID; }
};

class RayScene {
 public:
  static constexpr uint32_t kSceneGeometry = 0;
  static constexpr uint32_t kRevealGeometry = 1;
  static constexpr uint32_t kRevealGridGeometry = 2;

  // `reveals` are faces added by cutters, met unless both their sides are cut (adjacent openings
  // share no reveal); `reveal_grid` lines the elements' tubes through thick walls, met only where
  // one side is cut and the other is not. Either may be empty.
  RayScene(const Mesh& mesh, const Mesh& reveals, const Mesh& reveal_grid = Mesh());
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // Closest hit with t in (tnear, tfar); surfaces of geometry 0 inside any of `cutters` are skipped,
  // reveals as said above.
  Hit intersect(const Vec3& org, const Vec3& dir, float tnear, float tfar, const CutterSet* cutters) const;

 private:
  RTCScene scene_ = nullptr;
};

}  // namespace fenestra
