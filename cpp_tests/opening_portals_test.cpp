// The opening portals' sample() and pdf() tied together (as portal_sampler_test.cpp ties the
// elements'): the directions sample() draws from a point, histogrammed on the sphere, against the
// integral of pdf() over every cell (Pearson's chi-square, chi2.h), and pdf()'s integral over the
// sphere against 1 (every sample passes through a portal). Layouts: one window; a window, a
// skylight and a window in the opposite wall; two windows one behind the other (a direction through
// both has both densities); a window whose room lies on the other side (never a candidate). The
// same for the sky samples of a path with openings cut (sky_through_openings.h): a mixture of the
// sky's own (cosine-weighted under a uniform sky) and the openings'.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "chi2.h"
#include "trace/opening_portals.h"
#include "trace/sky_through_openings.h"

namespace fenestra {
namespace {

using fenestra_test::Chi2Result;
using fenestra_test::kSignificance;
using fenestra_test::next2;
using fenestra_test::SphereGrid;

constexpr float kSky = std::numeric_limits<float>::infinity();

// A cutter as OpeningDomain::through_wall builds it: corner, axes, and the normal out through the wall.
Cutter opening(const Vec3& corner, const Vec3& u, float width, const Vec3& v, float height, const Vec3& outward) {
  Cutter c;
  c.origin = corner;
  c.u_axis = u;
  c.v_axis = v;
  c.normal = outward;
  c.width = width;
  c.height = height;
  c.depth_back = 0.01f;
  c.depth_front = 0.3f;
  return c;
}

// A room 0 < x < 4, 0 < y < 5, 0 < z < 3.
const Cutter kSouthWindow = opening(Vec3(1, 0, 0.9f), Vec3(1, 0, 0), 1.6f, Vec3(0, 0, 1), 1.2f, Vec3(0, -1, 0));
const Cutter kNorthWindow = opening(Vec3(1.5f, 5, 1), Vec3(1, 0, 0), 1.0f, Vec3(0, 0, 1), 1.0f, Vec3(0, 1, 0));
const Cutter kSkylight = opening(Vec3(2, 3, 3), Vec3(1, 0, 0), 1.0f, Vec3(0, 1, 0), 0.8f, Vec3(0, 0, 1));
// A window in a second wall 1 m beyond the south one (a loggia's outer wall), overlapping it in view.
const Cutter kOuterWindow = opening(Vec3(0.5f, -1, 0.5f), Vec3(1, 0, 0), 2.0f, Vec3(0, 0, 1), 1.5f, Vec3(0, -1, 0));
// A window of the next room, whose room lies at y < -2: never a candidate from inside this one.
const Cutter kNeighbourWindow = opening(Vec3(1, -2, 1), Vec3(1, 0, 0), 1.0f, Vec3(0, 0, 1), 1.0f, Vec3(0, 1, 0));

struct Layout {
  std::string name;
  CutterSet openings;
  Vec3 from, normal;
};

std::vector<Layout> layouts() {
  return {{"one window", {kSouthWindow}, Vec3(1.3f, 2.2f, 0.8f), Vec3(0, 0, 1)},
          {"window, skylight, opposite window", {kSouthWindow, kSkylight, kNorthWindow}, Vec3(2.7f, 1.9f, 0.8f),
           Vec3(0, 0, 1)},
          {"a window behind a window", {kSouthWindow, kOuterWindow}, Vec3(2.2f, 1.5f, 1.4f), Vec3(0, -1, 0)},
          {"a window of the next room", {kNorthWindow, kNeighbourWindow}, Vec3(1.0f, 3.0f, 2.9f), Vec3(0, 0, -1)}};
}

bool draw(const OpeningPortals& portals, const Layout& l, Rng& rng, Vec3* d) {
  const float u_pick = rng.uniform();
  OpeningPortals::Sample s;
  const OpeningPortals::From from(portals, l.from, l.normal);
  if (!from.sample(u_pick, next2(rng), &s)) return false;
  *d = s.direction;
  EXPECT_NEAR(s.pdf, from.pdf(s.direction, kSky), 1e-4f * s.pdf) << l.name << ": a sample carries its own density";
  return true;
}

// A (theta, phi) grid split where the densities jump, at the rectangles' edges: at their corners'
// angles and at each edge's point nearest the layout's point, where its curve on the grid turns (a
// thin sliver of a cell there could fall between the quadrature's points).
SphereGrid grid_for(const Layout& l) {
  SphereGrid grid;
  grid.theta_res = 30;
  grid.phi_res = 60;
  auto split_at = [&](const Vec3& point) {
    const Vec3 d = (point - l.from).normalized();
    grid.theta_breaks.push_back(std::acos(std::clamp(double(d.z()), -1.0, 1.0)));
    grid.phi_breaks.push_back(std::atan2(double(d.y()), double(d.x())));
  };
  for (const Cutter& c : l.openings) {
    const Vec3 corners[4] = {c.origin, c.origin + c.width * c.u_axis, c.origin + c.width * c.u_axis + c.height * c.v_axis,
                             c.origin + c.height * c.v_axis};
    for (int e = 0; e < 4; ++e) {
      const Vec3 &a = corners[e], &b = corners[(e + 1) % 4];
      split_at(a);
      const float along = std::clamp((l.from - a).dot(b - a) / (b - a).squaredNorm(), 0.0f, 1.0f);
      split_at(a + along * (b - a));
    }
  }
  return grid;
}

TEST(OpeningPortals, SampleFollowsPdfChi2) {
  const std::vector<Layout> all = layouts();
  const double alpha = fenestra_test::sidak_correction(kSignificance, static_cast<int>(all.size()));
  constexpr int kSamples = 300000;
  for (const Layout& l : all) {
    const OpeningPortals portals(l.openings);
    const SphereGrid grid = grid_for(l);
    const Chi2Result r = fenestra_test::sphere_chi2_every_sample_drawn(
        grid, kSamples, 23, [&](Rng& rng, Vec3* d) { return draw(portals, l, rng, d); },
        [&](const Vec3& d) { return portals.pdf(l.from, l.normal, d.normalized(), kSky); }, alpha);
    EXPECT_TRUE(r.passed) << l.name << ": " << r.message;
  }
}

TEST(OpeningPortals, PdfIntegratesToOne) {
  for (const Layout& l : layouts()) {
    const OpeningPortals portals(l.openings);
    const double integral = fenestra_test::integrate_sphere(
        [&](const Vec3& d) { return portals.pdf(l.from, l.normal, d.normalized(), kSky); });
    EXPECT_NEAR(integral, 1.0, 2e-3) << l.name;
  }
}

TEST(OpeningPortals, OnlyPortalsOnTheRoomSideAndBeforeTheReachCount) {
  // From inside the room the next room's window is never drawn, and has no density.
  const OpeningPortals portals({kNorthWindow, kNeighbourWindow});
  const Vec3 x(2.0f, 3.0f, 1.5f);
  const Vec3 toward_neighbour = (Vec3(1.5f, -2, 1.5f) - x).normalized();
  EXPECT_EQ(portals.pdf(x, Vec3(0, -1, 0), toward_neighbour, kSky), 0.0f);
  Rng rng(5, 1);
  for (int i = 0; i < 1000; ++i) {
    OpeningPortals::Sample s;
    const float u_pick = rng.uniform();
    ASSERT_TRUE(OpeningPortals::From(portals, x, Vec3(0, 0, 1)).sample(u_pick, next2(rng), &s));
    EXPECT_GT(s.direction.y(), 0.0f) << "drawn toward the north window only";
    EXPECT_NEAR((x + s.distance * s.direction).y(), 5.0f, 1e-4f);
  }
  // A direction through the north window counts only when the portal is nearer than its reach.
  const Vec3 toward_north = (Vec3(2.0f, 5, 1.5f) - x).normalized();
  EXPECT_GT(portals.pdf(x, Vec3(0, 0, 1), toward_north, kSky), 0.0f);
  EXPECT_EQ(portals.pdf(x, Vec3(0, 0, 1), toward_north, 1.9f), 0.0f);
  // On the far side of every portal (outdoors, north of the room) nothing is drawn.
  OpeningPortals::Sample s;
  const OpeningPortals::From outdoors(portals, Vec3(2, 7, 1), Vec3(0, 0, 1));
  EXPECT_FALSE(outdoors.any());
  EXPECT_FALSE(outdoors.sample(0.5f, Vec2(0.5f, 0.5f), &s));
}

TEST(SkyThroughOpenings, SampleFollowsPdfChi2) {
  const UniformSky sky(Rgb::Constant(1000.0f / kPi));
  std::vector<Layout> all = layouts();
  all.push_back({"no opening a candidate (outdoors)", {kSouthWindow}, Vec3(2.0f, -3.0f, 0.5f), Vec3(0, 0, 1)});
  const double alpha = fenestra_test::sidak_correction(kSignificance, static_cast<int>(all.size()));
  constexpr int kSamples = 300000;
  for (const Layout& l : all) {
    const OpeningPortals portals(l.openings);
    const SkyThroughOpenings mixture(&sky, portals);
    const SphereGrid grid = grid_for(l);
    auto pdf = [&](const Vec3& d) { return mixture.pdf(l.from, l.normal, d.normalized()); };
    const Chi2Result r = fenestra_test::sphere_chi2_every_sample_drawn(
        grid, kSamples, 29,
        [&](Rng& rng, Vec3* d) {
          const Vec2 u = next2(rng);
          const float u_pick = rng.uniform();
          float density = 0.0f;
          return mixture.sample(l.from, l.normal, u, u_pick, d, &density);
        },
        pdf, alpha);
    EXPECT_TRUE(r.passed) << l.name << ": " << r.message;
    EXPECT_NEAR(fenestra_test::integrate_sphere(pdf), 1.0, 2e-3) << l.name;
  }
}

TEST(SkyThroughOpenings, EachSampleCarriesItsOwnDensity) {
  // What sample() returns with a direction is pdf() of that direction (the tracer divides by it).
  const UniformSky sky(Rgb::Constant(1.0f));
  const Layout l = layouts()[1];
  const OpeningPortals portals(l.openings);
  const SkyThroughOpenings mixture(&sky, portals);
  Rng rng(11, 1);
  int through = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec2 u = next2(rng);
    const float u_pick = rng.uniform();
    Vec3 d;
    float pdf = 0.0f;
    ASSERT_TRUE(mixture.sample(l.from, l.normal, u, u_pick, &d, &pdf));
    EXPECT_NEAR(pdf, mixture.pdf(l.from, l.normal, d), 1e-4f * pdf);
    through += u.x() >= SkyThroughOpenings::kSkyShare;
  }
  EXPECT_GT(through, 1000);
}

}  // namespace
}  // namespace fenestra
