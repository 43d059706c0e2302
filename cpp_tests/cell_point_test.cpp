// Points of the path records kept as places in their element's cell (trace/cell_point.h).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "trace/cell_point.h"
#include "trace/open_region.h"
#include "util/rng.h"

namespace fenestra {
namespace {

Element cell(float u0, float u1, float v0, float v1) {
  Element e;
  e.u0 = u0, e.u1 = u1, e.v0 = v0, e.v1 = v1;
  return e;
}

TEST(CellPoint, RoundTripIsWithinHalfAStepOfTheCell) {
  // A cell far from its panel's corner, where a panel point's own float rounding is largest.
  const Element e = cell(37.5f, 37.8f, 11.1f, 11.4f);
  Rng rng(7, 1);
  double worst_u = 0.0, worst_v = 0.0, sum_u = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const PanelPoint p{e.u0 + rng.uniform() * e.width(), e.v0 + rng.uniform() * e.height()};
    double u, v;
    CellPoint::of(e, p).to_panel<double>(e.u0, e.u1, e.v0, e.v1, &u, &v);
    worst_u = std::max(worst_u, std::abs(u - p.u));
    worst_v = std::max(worst_v, std::abs(v - p.v));
    sum_u += u - p.u;
  }
  // Half a step of the cell, plus the panel point's own float rounding at 37 m (2^-18 m).
  const double bound = 0.5 * 0.3 / CellPoint::kSteps + std::ldexp(1.0, -18);
  EXPECT_LE(worst_u, bound);
  EXPECT_LE(worst_v, bound);
  // Rounding to the nearest step moves points as often one way as the other: the mean offset is
  // within 5 standard errors of zero (uniform rounding error: step / sqrt(12) each).
  const double step = 0.3 / CellPoint::kSteps;
  EXPECT_LT(std::abs(sum_u / n), 5.0 * step / std::sqrt(12.0 * n) + std::ldexp(1.0, -19));
}

TEST(CellPoint, PointsOnOrPastTheEdgesBelongToTheCell) {
  const Element e = cell(1.0f, 1.5f, 2.0f, 2.5f);
  const CellPoint lo = CellPoint::of(e, {0.9f, 1.9f}), hi = CellPoint::of(e, {1.6f, 2.6f});
  EXPECT_EQ(lo.s, 0);
  EXPECT_EQ(lo.t, 0);
  EXPECT_EQ(hi.s, 65535);
  EXPECT_EQ(hi.t, 65535);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const CellPoint bad = CellPoint::of(e, {nan, nan});
  EXPECT_EQ(bad.s, 0);
  EXPECT_EQ(bad.t, 0);
  const CellPoint flat = CellPoint::in_cell({1.2f, 2.2f}, 1.0f, 1.0f, 2.0f, 2.0f);  // no width: the corner
  EXPECT_EQ(flat.s, 0);
}

TEST(CellPoint, OpenRegionTestsTheSamePlaceAsThePanelPoint) {
  // A 1 x 1 m panel in 0.25 m elements; an opening whose edges lie between the grid lines.
  Mesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 1), Vec3(0, 0, 1)};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.triangle_material = {0, 0};
  mesh.triangle_group = {-1, -1};
  OpeningDomainSelection selection;
  selection.materials = {"domain"};
  selection.element_size = 0.25f;
  const OpeningDomain domain = OpeningDomain::build(mesh, {"domain"}, selection);
  ASSERT_EQ(domain.element_count(), 16u);
  // Its left edge is on a grid line: the elements it covers are open up to their corners.
  const PanelRectangle opening{0, 0.25, 0.62, 0.1, 0.9};
  const OpenRegion region(domain, {opening});
  Rng rng(3, 1);
  int disagree = 0, points = 0, covered = 0;
  for (size_t k = 0; k < domain.element_count(); ++k) {
    const Element& e = domain.elements()[k];
    for (int i = 0; i < 2000; ++i, ++points) {
      const PanelPoint p{e.u0 + rng.uniform() * e.width(), e.v0 + rng.uniform() * e.height()};
      disagree += region.is_open(static_cast<int32_t>(k), p) != region.is_open(static_cast<int32_t>(k), CellPoint::of(e, p));
    }
    // The cell's corners belong to it, as for panel points: a whole element is open or closed.
    const bool whole = region.is_open(static_cast<int32_t>(k), PanelPoint{0.5f * (e.u0 + e.u1), 0.5f * (e.v0 + e.v1)});
    if (e.u0 >= 0.25f && e.u1 <= 0.62f && e.v0 >= 0.1f && e.v1 <= 0.9f) {
      ++covered;
      EXPECT_TRUE(region.is_open(static_cast<int32_t>(k), CellPoint{0, 0}));
      EXPECT_TRUE(region.is_open(static_cast<int32_t>(k), CellPoint{65535, 65535}));
      EXPECT_TRUE(whole);
    }
  }
  EXPECT_EQ(covered, 2);
  // Only points within half a step (1.9 micrometres here) of the opening's edges can differ: of
  // 32 000 uniform points, the expected number is ~0.03.
  EXPECT_LE(disagree, 1) << "of " << points;
}

}  // namespace
}  // namespace fenestra
