#pragma once
// The openings really cut (a check with real cutters, `evaluate`) as portals of the sky: every
// vertex of a path inside the room draws one direction through an opening, which the tracer weighs
// by MIS against BSDF and sky sampling. Without it, light from outside reaches the room only
// through the directions the BSDF or the whole sky happen to aim through a hole, which in a room is
// the rare case that carries the light. What draws a direction and what gives its density sit side
// by side (sample, pdf), tied by cpp_tests/opening_portals_test.cpp.
//
// A portal is an opening's rectangle on the room-side face of its panel (the cutter's own plane).
// From a point x an opening is a candidate only when x lies on its room side; one is picked with
// probability proportional to an estimate of its solid angle times the receiver's cosine toward
// its centre, then a direction uniform in its solid angle (SphericalRectangle). A direction's
// density sums every candidate portal it crosses before `reach` (the light found along it is what
// lies beyond the portal: nearer, the sample found nothing). Curved panels' openings (chart
// rectangles) are no portals: BSDF and sky sampling still find their light.
#include <vector>

#include "math/vec.h"
#include "scene/cutter.h"

namespace fenestra {

class OpeningPortals {
 public:
  OpeningPortals() = default;
  explicit OpeningPortals(const CutterSet& openings);

  bool empty() const { return portals_.empty(); }
  size_t size() const { return portals_.size(); }

  struct Sample {
    Vec3 direction;        // unit
    float distance = 0.0f;  // from x to the portal's point along `direction`
  };
  // Whether any portal is a candidate from x (receiver normal n): sample() then draws a direction.
  bool candidates(const Vec3& x, const Vec3& n) const;
  // A direction from x (receiver normal n) through a portal, from u_pick and uv uniform in [0, 1);
  // false when no portal is a candidate from x.
  bool sample(const Vec3& x, const Vec3& n, float u_pick, const Vec2& uv, Sample* out) const;
  // The solid-angle density with which sample(x, n, ...) yields `dir` through a portal nearer than
  // `reach` (meters; infinity for a ray that reaches the sky). `candidates`, when given: whether
  // any portal is a candidate from x (sample() then draws a direction).
  float pdf(const Vec3& x, const Vec3& n, const Vec3& dir, float reach, bool* candidates = nullptr) const;

 private:
  struct Portal {
    Vec3 corner, u, v;  // corner + s u + t v, s, t in [0, 1]
    Vec3 unit_u, unit_v;
    float width = 0.0f, height = 0.0f;
    Vec3 outward;       // unit; the room lies on its negative side
    Vec3 centre;
    float area = 0.0f;
  };
  // Portal k's weight from x (0 when it is no candidate): an estimate of its solid angle times
  // the cosine at x toward its centre (floored, so that a portal low on x's horizon stays likely).
  float weight(const Portal& p, const Vec3& x, const Vec3& n) const;

  std::vector<Portal> portals_;
};

}  // namespace fenestra
