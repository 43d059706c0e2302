// Openings whose edges lie between grid lines: the path records evaluate them from where each
// path met the domain, against `evaluate` with the rectangles really cut.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "annual/annual_contributions.h"
#include "solve/region_search.h"
#include "test_scenes.h"
#include "trace/contributions.h"
#include "trace/evaluate.h"

namespace fenestra {
namespace {

using test::room_with_neighbour;
using test::TempDir;
using test::within_sigma;

// The rectangle [u0, u1] x [v0, v1] of panel p in world corners (for evaluate).
Rectangle world_corners(const OpeningDomain& domain, const PanelRectangle& r) {
  const Panel& p = domain.panels()[r.panel];
  auto at = [&](double u, double v) {
    return Vec3(p.origin + static_cast<float>(u) * p.u_axis + static_cast<float>(v) * p.v_axis);
  };
  return {at(r.u0, r.v0), at(r.u1, r.v0), at(r.u1, r.v1), at(r.u0, r.v1)};
}

int wall_panel(const Scene& scene) {
  for (size_t p = 0; p < scene.domain.panels().size(); ++p)
    if (std::abs(scene.domain.panels()[p].normal.z()) < 0.5f) return static_cast<int>(p);
  return -1;
}

TEST(OpenRegion, GridAlignedRegionEqualsTheElementMask) {
  TempDir dir;
  const Scene scene = room_with_neighbour(dir, 1 << 10);
  const Contributions c = compute_contributions(scene);
  const int wall = wall_panel(scene);
  const PanelRectangle r{wall, 0.5, 2.0, 0.5, 2.0};
  std::vector<uint8_t> mask(scene.domain.element_count(), 0);
  for (size_t k = 0; k < mask.size(); ++k) {
    const Element& e = scene.domain.elements()[k];
    const PanelPoint q = scene.domain.panel_point(e.panel, e.center);
    mask[k] = e.panel == wall && q.u > r.u0 && q.u < r.u1 && q.v > r.v0 && q.v < r.v1;
  }
  ASSERT_EQ(std::count(mask.begin(), mask.end(), 1), 9);
  const SensorValues a = c.evaluate(mask), b = c.evaluate(OpenRegion(scene.domain, {r}));
  for (Eigen::Index i = 0; i < a.value.size(); ++i) {
    EXPECT_NEAR(a.value[i], b.value[i], 1e-9 * (1.0 + a.value[i])) << "sensor " << i;
    EXPECT_NEAR(a.standard_error[i], b.standard_error[i], 1e-9 * (1.0 + a.standard_error[i])) << "sensor " << i;
  }
}

TEST(OpenRegion, RectanglesOffTheGridMatchEvaluate) {
  TempDir dir;
  const Scene scene = room_with_neighbour(dir, 1 << 13);
  const Contributions c = compute_contributions(scene);
  const int wall = wall_panel(scene);
  const int roof = 1 - wall;
  // A window with every edge between grid lines, a narrow one, and a skylight (0.37 m off the grid).
  const std::vector<PanelRectangle> rects = {{wall, 0.33, 1.61, 0.71, 1.93}, {wall, 2.6, 2.85, 0.2, 2.3},
                                             {roof, 1.37, 2.12, 0.87, 1.49}};
  std::vector<OpeningInput> cuts;
  for (const auto& r : rects) cuts.push_back(world_corners(scene.domain, r));
  const SensorValues exact = c.evaluate(OpenRegion(scene.domain, rects));
  const SensorValues truth = evaluate_openings(scene, cuts);
  for (Eigen::Index i = 0; i < exact.value.size(); ++i) {
    EXPECT_GT(truth.value[i], 0.0);
    EXPECT_TRUE(within_sigma(exact.value[i], exact.standard_error[i], truth.value[i], truth.standard_error[i]))
        << "sensor " << i;
  }
  // And the test can tell: the nearest whole-element window differs.
  std::vector<uint8_t> mask(scene.domain.element_count(), 0);
  for (size_t k = 0; k < mask.size(); ++k) {
    const Element& e = scene.domain.elements()[k];
    mask[k] = OpenRegion(scene.domain, rects).is_open(static_cast<int32_t>(k), scene.domain.panel_point(e.panel, e.center));
  }
  const SensorValues snapped = c.evaluate(mask);
  int distinct = 0;
  for (Eigen::Index i = 0; i < exact.value.size(); ++i)
    distinct += !within_sigma(snapped.value[i], snapped.standard_error[i], truth.value[i], truth.standard_error[i]);
  EXPECT_GT(distinct, 0);
}

TEST(RegionSearch, StripsCoverEveryPointInOneRectangleOnly) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(0.0, 4.0);
  auto rectangle = [&] {
    const double a = x(rng), b = x(rng), c = x(rng), d = x(rng);
    return PanelRectangle{0, std::min(a, b), std::max(a, b), std::min(c, d), std::max(c, d)};
  };
  auto inside = [](const PanelRectangle& r, double u, double v) { return u > r.u0 && u < r.u1 && v > r.v0 && v < r.v1; };
  int tested = 0;
  for (int trial = 0; trial < 400; ++trial) {
    PanelRectangle a = rectangle(), b = a;
    // One edge, two, or a new rectangle.
    if (trial % 3 == 0) b.u1 = std::max(b.u0 + 0.01, b.u1 + x(rng) - 2.0);
    if (trial % 3 == 1) b.v0 = std::min(b.v1 - 0.01, b.v0 + x(rng) - 2.0), b.u0 = std::min(b.u1 - 0.01, b.u0 + 0.1);
    if (trial % 3 == 2) b = rectangle();
    const std::vector<PanelRectangle> strips = changed_strips(a, b);
    for (int k = 0; k < 200; ++k) {
      const double u = x(rng), v = x(rng);
      if (inside(a, u, v) == inside(b, u, v)) continue;
      ++tested;
      bool covered = false;
      for (const PanelRectangle& s : strips) covered = covered || (u >= s.u0 && u <= s.u1 && v >= s.v0 && v <= s.v1);
      EXPECT_TRUE(covered) << "trial " << trial << " point " << u << ", " << v;
    }
  }
  EXPECT_GT(tested, 1000);
  EXPECT_TRUE(changed_strips(PanelRectangle{0, 1, 2, 1, 2}, PanelRectangle{0, 1, 2, 1, 2}).empty());
}

// The incremental values (only the paths that met the swept strips re-evaluated) equal a full
// evaluation of the same rectangles, over a seeded walk of edge moves of every size.
TEST(RegionSearch, IncrementalValuesEqualAFullEvaluation) {
  TempDir dir;
  const Scene scene = room_with_neighbour(dir, 1 << 9);
  const Contributions c = compute_contributions(scene);
  const int wall = wall_panel(scene), roof = 1 - wall;
  std::vector<PanelRectangle> current = {{wall, 1.0, 2.0, 0.5, 1.5}, {roof, 1.0, 2.5, 1.0, 2.0}};
  RegionSearch search(c, scene.domain, current);
  std::mt19937 rng(3);
  const std::vector<double> steps = {0.5, 0.25, 0.125, 0.01, 0.37};
  size_t accepted = 0;
  for (int move = 0; move < 60; ++move) {
    std::vector<PanelRectangle> candidate = current;
    PanelRectangle& r = candidate[rng() % 2];
    const double by = (rng() % 2 ? 1.0 : -1.0) * steps[rng() % steps.size()];
    double* edges[] = {&r.u0, &r.u1, &r.v0, &r.v1};
    *edges[rng() % 4] += by;
    if (move % 5 == 0) *edges[rng() % 4] -= by;  // a second edge
    if (!(r.u1 - r.u0 > 0.05 && r.v1 - r.v0 > 0.05 && r.u0 >= 0.0 && r.v0 >= 0.0 && r.u1 <= 2.5 && r.v1 <= 2.5))
      continue;
    const Eigen::VectorXd tried = search.try_region(candidate);
    const SensorValues full = c.evaluate(OpenRegion(scene.domain, candidate));
    for (Eigen::Index i = 0; i < tried.size(); ++i)
      ASSERT_NEAR(tried[i], full.value[i], 1e-9 * (1.0 + full.value[i])) << "move " << move << " sensor " << i;
    if (rng() % 2) {
      search.accept();
      current = candidate;
      ++accepted;
    }
  }
  EXPECT_GT(accepted, 10u);
  // The cost model counts the index as 2 x the path records (docs/cost.md).
  size_t record_bytes = 0;
  for (const SensorRecord& r : c.records) record_bytes += r.memory_bytes();
  EXPECT_LT(static_cast<double>(search.memory_bytes()), 2.0 * static_cast<double>(record_bytes));
  EXPECT_GT(static_cast<double>(search.memory_bytes()), 0.3 * static_cast<double>(record_bytes));
  // Fewer paths than a full evaluation per try: the strips hold a fraction of the met points.
  EXPECT_LT(search.paths_evaluated(), 60u * scene.sensors.size() * c.paths_per_sensor / 2);
}

}  // namespace
}  // namespace fenestra
