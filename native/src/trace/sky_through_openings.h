#pragma once
// The sky samples of a path with the openings really cut: a mixture of the sky's own importance
// (with probability kSkyShare) and directions through the openings (opening_portals.h), wherever
// any opening is a candidate; elsewhere the sky's own samples alone. From inside a room most of the
// sky lies behind its walls: the openings' samples find the part that does not, and the sky's own
// stay for light through holes that are no openings and for a bright sky region (the sun's aureole)
// that the openings' uniform solid angle would miss. One sample, one shadow ray, as before; the
// mixture's density is what MIS weighs against the BSDF's. sample() and pdf() side by side, tied
// by cpp_tests/opening_portals_test.cpp.
#include "daylight/sky.h"
#include "trace/opening_portals.h"

namespace fenestra {

class SkyThroughOpenings {
 public:
  static constexpr float kSkyShare = 0.25f;

  // `sky` may be null until a path asks (a scene whose sky is built later).
  SkyThroughOpenings(const Sky* sky, const OpeningPortals& openings) : sky_(sky), openings_(openings) {}

  // Whether there are openings to sample at all.
  bool has_openings() const { return !openings_.empty(); }

  // A direction from x (receiver normal n) from u and u_pick uniform in [0, 1) (u_pick chooses the
  // opening), with its density; false when none was drawn.
  bool sample(const Vec3& x, const Vec3& n, const Vec2& u, float u_pick, Vec3* dir, float* pdf) const;
  // The solid-angle density with which sample(x, n, ...) yields `dir`.
  float pdf(const Vec3& x, const Vec3& n, const Vec3& dir) const;

 private:
  static float mixture(const OpeningPortals::From& from, float sky_pdf, float through_pdf);

  const Sky* sky_;
  const OpeningPortals& openings_;
};

}  // namespace fenestra
