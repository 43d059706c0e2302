#pragma once
// The openings really cut (a check with real cutters, `evaluate`) as portals of the sky: a path's
// sky samples go through them (sky_through_openings.h), weighed by MIS against BSDF sampling.
// Without it, light from outside reaches a room only along the directions the BSDF or the whole
// sky happen to aim through a hole, which inside a room is the rare case that carries the light.
// What draws a direction and what gives its density sit side by side (From::sample, From::pdf),
// tied by cpp_tests/opening_portals_test.cpp.
//
// A portal is an opening's rectangle on the room-side face of its panel (the cutter's own plane).
// From a point x an opening is a candidate only when x lies on its room side; one is picked with
// probability proportional to an estimate of its solid angle times the receiver's cosine toward
// its centre, then a direction uniform in its solid angle (SphericalRectangle). A direction's
// density sums every candidate portal it crosses before `reach` (the light found along it is what
// lies beyond the portal: nearer, the sample found nothing). Curved panels' openings (chart
// rectangles) are no portals: BSDF and sky sampling still find their light.
#include <array>
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
    Vec3 direction;         // unit
    float distance = 0.0f;  // from x to the portal's point along `direction`
    float pdf = 0.0f;       // its solid-angle density: From::pdf toward the sky, to rounding
  };

 private:
  struct Portal;

 public:
  // The portals seen from x (receiver normal n): each one's weight computed once, for the samples
  // and densities asked at that point.
  class From {
   public:
    From(const OpeningPortals& portals, const Vec3& x, const Vec3& n);
    // Whether any portal is a candidate: sample() then draws a direction.
    bool any() const { return total_ > 0.0f; }
    // A direction through a portal from u_pick and uv uniform in [0, 1), with its density toward
    // the sky; false when none was drawn.
    bool sample(float u_pick, const Vec2& uv, Sample* out) const;
    // The solid-angle density with which sample() yields `dir` through a portal nearer than
    // `reach` (meters; infinity for a ray that reaches the sky).
    float pdf(const Vec3& dir, float reach) const;

   private:
    float weight(size_t k) const { return k < inline_.size() ? inline_[k] : spilled_[k - inline_.size()]; }
    // Portal k's share of the density toward dir (before dividing by the total): its weight over
    // its solid angle when dir crosses it nearer than reach, else 0.
    float crossing_density(size_t k, const Vec3& dir, float reach) const;

    const OpeningPortals& portals_;
    Vec3 x_, n_;
    float total_ = 0.0f;
    std::array<float, 8> inline_{};
    std::vector<float> spilled_;  // the weights of portals past the eighth
  };

  // From(*this, x, n).pdf(dir, reach), for a direction already drawn.
  float pdf(const Vec3& x, const Vec3& n, const Vec3& dir, float reach) const { return From(*this, x, n).pdf(dir, reach); }

 private:
  struct Portal {
    Vec3 corner, u, v;  // corner + s u + t v, s, t in [0, 1]
    Vec3 unit_u, unit_v;
    float width = 0.0f, height = 0.0f;
    Vec3 outward;  // unit; the room lies on its negative side
    Vec3 centre;
    float area = 0.0f;
  };
  // Portal p's weight from x (0 when it is no candidate): an estimate of its solid angle times
  // the cosine at x toward its centre (floored, so that a portal low on x's horizon stays likely).
  static float weight(const Portal& p, const Vec3& x, const Vec3& n);

  std::vector<Portal> portals_;
};

}  // namespace fenestra
