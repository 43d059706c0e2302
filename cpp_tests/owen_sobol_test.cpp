// The stratified sampler: Owen-scrambled Sobol pairs (sampling/owen_sobol.h) and the per-path
// samples built on them (trace/path_samples.h). A scrambled (0,2)-sequence must keep its
// stratification (every 2^m aligned points form a (0,m,2)-net), every point must be uniform over
// the scrambles (unbiased estimates), pairs must be independent of one another, and the estimate
// of a known integral must be unbiased with far less variance than independent points.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "chi2.h"
#include "student_t.h"
#include "sampling/owen_sobol.h"
#include "trace/path_samples.h"
#include "trace/replicates.h"
#include "util/rng.h"

namespace fenestra {
namespace {

using fenestra_test::kSignificance;

// Index of the elementary interval [i / 2^a, (i + 1) / 2^a) x [j / 2^b, (j + 1) / 2^b) holding p.
int elementary_cell(const Vec2& p, int a, int b) {
  const int i = static_cast<int>(std::floor(p.x() * (1 << a)));
  const int j = static_cast<int>(std::floor(p.y() * (1 << b)));
  return i * (1 << b) + j;
}

TEST(OwenSobol, EveryAlignedBlockIsANet) {
  // The first 2^m points, and the next 2^m, of any pair and scramble put one point in every
  // elementary interval of area 2^-m, whatever its shape.
  for (const uint64_t seed : {1ull, 77ull, 123456789ull})
    for (uint32_t pair = 0; pair < 9; ++pair)
      for (int m = 0; m <= 10; ++m)
        for (uint32_t block = 0; block < 2; ++block)
          for (int a = 0; a <= m; ++a) {
            std::set<int> cells;
            for (uint32_t k = 0; k < (1u << m); ++k)
              cells.insert(elementary_cell(owen_sobol_2d(block * (1u << m) + k, pair, seed), a, m - a));
            ASSERT_EQ(cells.size(), 1u << m) << "seed " << seed << " pair " << pair << " m " << m << " shape " << a;
          }
}

TEST(OwenSobol, PointsStayInTheUnitSquare) {
  for (uint32_t i = 0; i < 100000; ++i) {
    const Vec2 p = owen_sobol_2d(i * 7919u, i % 9, i);
    ASSERT_GE(p.x(), 0.0f);
    ASSERT_LT(p.x(), 1.0f);
    ASSERT_GE(p.y(), 0.0f);
    ASSERT_LT(p.y(), 1.0f);
  }
}

// Pearson's chi-square of n points on a g x g grid against the uniform density.
fenestra_test::Chi2Result uniform_chi2(const std::vector<Vec2>& points, int g, double significance) {
  std::vector<double> observed(g * g, 0.0), expected(g * g, static_cast<double>(points.size()) / (g * g));
  for (const Vec2& p : points)
    observed[std::min(g - 1, static_cast<int>(p.x() * g)) * g + std::min(g - 1, static_cast<int>(p.y() * g))] += 1;
  return fenestra_test::pearson_chi2(observed, expected, significance);
}

TEST(OwenSobol, EachPointIsUniformOverTheScrambles) {
  // Unbiasedness: a given point of the sequence, over independent scrambles, is uniform on the
  // square. Three indices (the first, a middle and a late one), Sidak-corrected.
  const double significance = 1.0 - std::pow(1.0 - kSignificance, 1.0 / 3.0);
  for (const uint32_t index : {0u, 5u, 1000u}) {
    std::vector<Vec2> points;
    for (uint64_t seed = 0; seed < 200000; ++seed) points.push_back(owen_sobol_2d(index, 3, seed));
    const auto r = uniform_chi2(points, 20, significance);
    EXPECT_TRUE(r.passed) << "index " << index << ": " << r.message;
  }
}

TEST(OwenSobol, PairsAreIndependent) {
  // The x of two different pairs of one point, over scrambles: uniform on the square (a joint
  // density; correlated pairs would pile up on a curve).
  std::vector<Vec2> joint;
  for (uint64_t seed = 0; seed < 200000; ++seed)
    joint.emplace_back(owen_sobol_2d(17, 0, seed).x(), owen_sobol_2d(17, 1, seed).x());
  const auto r = uniform_chi2(joint, 20, kSignificance);
  EXPECT_TRUE(r.passed) << r.message;
  // And the same pair at two indices of one scramble are as stratified as the net demands, not
  // equal: the shuffle differs by pair.
  EXPECT_NE(owen_sobol_2d(1, 0, 9).x(), owen_sobol_2d(1, 1, 9).x());
}

TEST(OwenSobol, QuarterDiscIntegralIsUnbiasedWithLessVariance) {
  // The area of the quarter disc x^2 + y^2 < 1 (pi / 4) from 256 points: the mean over 4000
  // scrambles within 4 standard errors of pi / 4, and the variance at least 8x below that of 256
  // independent points (theory: O(n^-1.5) against n^-1 for an integrand with a smooth
  // discontinuity, sqrt(256) = 16 up to a constant; measured 14x).
  constexpr int kPoints = 256, kTrials = 4000;
  const double exact = 3.14159265358979323846 / 4.0;
  double sum = 0.0, sum_sq = 0.0;
  for (int t = 0; t < kTrials; ++t) {
    int inside = 0;
    for (uint32_t i = 0; i < kPoints; ++i) {
      const Vec2 p = owen_sobol_2d(i, 4, 1000 + t);
      inside += p.x() * p.x() + p.y() * p.y() < 1.0f;
    }
    const double estimate = static_cast<double>(inside) / kPoints;
    sum += estimate;
    sum_sq += estimate * estimate;
  }
  const double mean = sum / kTrials, variance = (sum_sq / kTrials - mean * mean) * kTrials / (kTrials - 1);
  EXPECT_NEAR(mean, exact, 4.0 * std::sqrt(variance / kTrials));
  const double independent_variance = exact * (1.0 - exact) / kPoints;
  EXPECT_LT(variance, independent_variance / 8.0) << "variance " << variance << " vs independent "
                                                     << independent_variance;
}

TEST(PathSamples, ReplicateGroupsAreScrambledIndependently) {
  // Paths p and p + 1 fall in different replicate groups: different scrambles. Paths p and
  // p + kReplicates are consecutive points of one group's scramble.
  const PathSamples a(1, 0, 0), b(1, 0, 1), c(1, 0, kReplicates);
  EXPECT_NE(a.get2d(PathSamples::kFirstBounce).x(), b.get2d(PathSamples::kFirstBounce).x());
  // Consecutive points of one scramble: the first two are one in each half of the square.
  const float x0 = a.get2d(PathSamples::kFirstBounce).x(), x1 = c.get2d(PathSamples::kFirstBounce).x();
  EXPECT_NE(x0 < 0.5f, x1 < 0.5f);
  // Another sensor or seed: another scramble.
  EXPECT_NE(PathSamples(1, 1, 0).get2d(PathSamples::kFirstBounce).x(), x0);
  EXPECT_NE(PathSamples(2, 0, 0).get2d(PathSamples::kFirstBounce).x(), x0);
  // Each group's paths are a net: 64 paths of group 3 fill the 8 x 8 grid.
  std::set<int> cells;
  for (size_t k = 0; k < 64; ++k)
    cells.insert(elementary_cell(PathSamples(5, 2, 3 + k * kReplicates).get2d(PathSamples::kSensorSky), 3, 3));
  EXPECT_EQ(cells.size(), 64u);
}

TEST(PathSamples, IndependentSamplerGivesNone) {
  RenderSettings render;
  EXPECT_TRUE(path_samples(render, 1, 0, 0).has_value());  // sobol is the default
  render.sampler = RenderSettings::Sampler::kIndependent;
  EXPECT_FALSE(path_samples(render, 1, 0, 0).has_value());
}

TEST(StudentT, QuantilesMatchPublishedValues) {
  // scipy.stats.t.isf(p / 2, nu) for the two-sided tail of a normal 4 sigma (p = 6.334e-5) and
  // 3 sigma, and the normal limit: the bounds within_sigma (test_scenes.h) uses.
  EXPECT_NEAR(test::normal_equivalent_t(4.0, 15.0), 5.48038, 1e-4);
  EXPECT_NEAR(test::normal_equivalent_t(4.0, 30.0), 4.64512, 1e-4);
  EXPECT_NEAR(test::normal_equivalent_t(3.0, 20.0), 3.42215, 1e-4);
  EXPECT_NEAR(test::normal_equivalent_t(4.0, 1e7), 4.0, 1e-3);
  EXPECT_NEAR(test::student_t_two_sided(2.131847, 4.0), 0.1, 1e-6);  // the tables: t(0.95, 4) = 2.131847
}

}  // namespace
}  // namespace fenestra
