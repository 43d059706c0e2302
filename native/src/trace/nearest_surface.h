#pragma once
// The scene's surface nearest to a point, within a radius: Embree's point query over the triangles.
// Setup checks use it to find sensors lying on (or a few centimetres off) a wall, floor or the
// opening domain, where a sensor's light is not what a person measuring the room would read.
#include <embree3/rtcore.h>

#include <cstdint>
#include <functional>

#include "scene/mesh.h"

namespace fenestra {

struct NearestHit {
  float distance = 0.0f;  // meters; the radius asked for when nothing is nearer
  int triangle = -1;      // -1 when no triangle is within the radius
  bool found() const { return triangle >= 0; }
};

class NearestSurface {
 public:
  explicit NearestSurface(const Mesh& mesh);  // keeps a reference: `mesh` must outlive this
  ~NearestSurface();
  NearestSurface(const NearestSurface&) = delete;
  NearestSurface& operator=(const NearestSurface&) = delete;

  // Whether triangle t, whose point nearest to the query is `closest`, counts.
  using Filter = std::function<bool(uint32_t t, const Vec3& closest)>;

  // The nearest triangle to `p` within `radius` (meters), among those `counts` accepts (all when
  // empty). Thread safe.
  NearestHit nearest(const Vec3& p, float radius, const Filter& counts = Filter()) const;

 private:
  const Mesh& mesh_;
  RTCScene scene_ = nullptr;
};

// The nearest face within `radius` of a sensor at `p` facing `n` that cuts through its hemisphere:
// a face parallel to the sensor (|cos| >= 0.9) and behind it, like the floor under a workplane
// sensor, does not count. With `only`, a triangle t counts only where only[t] is non-zero.
NearestHit nearest_in_view(const NearestSurface& surfaces, const Mesh& mesh, const Vec3& p, const Vec3& n, float radius,
                           const std::vector<uint8_t>* only = nullptr);

// The point of triangle (a, b, c) closest to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace fenestra
